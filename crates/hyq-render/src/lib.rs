//! Seeing an episode without a display or a GPU: frames of the robot (`rgb_array`), animated
//! GIFs and PNG frames, and per-episode reward plots.
//!
//! - [`Renderer`] draws a [`Scene`] (the robot's pose, its contacts, the goal and a text
//!   [`Overlay`]) into a [`Frame`]: 8-bit RGB, `height × width × 3`, row-major, the exact
//!   buffer of Gymnasium's `render_mode="rgb_array"`. A perspective [`Camera`] follows the
//!   trunk; the ground has a 1 m grid, and a height field ([`Scene::with_terrain`]) is drawn
//!   shaded with the grid draped over it; the trunk box, leg capsules and foot spheres are the
//!   model's collision shapes, feet in contact turn orange and a trunk touching the ground
//!   turns red. Under the velocity-command task ([`Scene::with_velocity`]) the command and the
//!   trunk's measured velocity are arrows on the ground under the trunk and rows of the
//!   overlay ([`VelocityHud`]). Everything is drawn on the CPU with tiny-skia's anti-aliased 2-D rasteriser
//!   (this crate only projects and orders the shapes), text with a bundled font.
//! - [`write_gif`] / [`GifWriter`] (streaming) and [`write_png`] / [`PngSequence`] write
//!   frames to files.
//! - [`PlotRecord`] is one line of the environment's JSONL log; [`plot_jsonl`] turns a log into
//!   two PNG plots per episode ([`plot_reward_terms`], [`plot_distance`]): every reward term, the
//!   multipliers, the penalties and the cumulative reward over time, and D_n over time beside
//!   the spec's §4.3 curve R_e(D_n) with the episode's points on it.
//!
//! The crate takes plain values: a [`hyq_physics::RobotModel`], poses, contact flags and
//! numbers. It depends on no physics engine, and on no environment unless its `env` feature is
//! on: then `env_scene` builds the scene of an hyq-env `Env`'s current state, the one helper
//! the CLI's `hyq render` and the Python binding's `rgb_array` share.
//!
//! # Example: a frame, as `rgb_array` returns it
//!
//! ```
//! use hyq_physics::na::Point3;
//! use hyq_render::{Overlay, RenderConfig, Renderer, RobotPose, Scene};
//!
//! let model = hyq_physics::bundled::hyq();
//! // Build once per environment; it keeps its buffers.
//! let mut renderer = Renderer::new(model.clone(), RenderConfig::default())?;
//!
//! let state = model.spawn_state(); // in the env: the backend's trunk pose and joint angles
//! let contacts = [true, true, true, true, false]; // Backend::contacts: feet, then trunk
//! let scene = Scene::new(RobotPose::Joints { trunk: &state.trunk.pose, q: &state.q }, &contacts)
//!     .with_goal(Point3::new(5.0, 0.0, 0.6))
//!     .with_overlay(Overlay { time_s: 0.0, distance_to_goal_m: 5.0, episode_return: 0.0 });
//! let frame = renderer.render(&scene)?;
//!
//! assert_eq!(frame.shape(), [360, 480, 3]); // NumPy: np.frombuffer(rgb, np.uint8).reshape(shape)
//! assert_eq!(frame.rgb.len(), 360 * 480 * 3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Example: an episode to a GIF, and its log to plots
//!
//! ```no_run
//! # use hyq_render::*;
//! # fn frames() -> Vec<Frame> { Vec::new() }
//! let mut gif = GifWriter::create("episode.gif", 480, 360, 25.0)?;
//! for frame in frames() {
//!     gif.push(&frame)?; // streamed: frames are not kept in memory
//! }
//! gif.finish()?;
//!
//! // The run's exp_rew_scaling (None when r_e was off) and env step (s).
//! let options = PlotOptions { k_exp: Some(5.0), env_dt_s: Some(0.01), ..PlotOptions::default() };
//! let plots = plot_jsonl("episode.jsonl", &options, "plots/")?.plots;
//! println!("{}", plots[0].rewards.display()); // plots/episode_001_rewards.png
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! `cargo run --release -p hyq-render --example kinematic_demo -- DIR` writes a GIF, PNG frames,
//! a JSONL log and its plots for a scripted (kinematic, not simulated) trot.
//!
//! # Speed
//!
//! About 3 ms to render a 480 × 360 frame, and GIF writing bound by its colour quantisation:
//! the figures, and the bench that measures them (`cargo bench -p hyq-render --bench
//! render_frame`), are in `docs/benchmarks.md`.
//!
//! # Limits
//!
//! - Shapes are drawn back to front by their centre's distance from the camera (the painter's
//!   algorithm), not with a depth buffer: two shapes that interpenetrate are drawn one over
//!   the other. The robot's parts are convex and mostly apart, so this rarely shows.
//! - Cylinders are drawn as capsules; a collision shape of a kind this crate does not know is
//!   neither drawn nor shadowed. Meshes never reach it (the model refuses them).
//! - The overlay's text has a fixed size (13 px): a frame under about 300 × 190 px is drawn
//!   without the overlay rather than with a panel that hides the robot.
//! - Text is DejaVu Sans cut to Latin, Greek and a few symbols (`assets/fonts/README.md`).

mod camera;
mod clip;
#[cfg(feature = "env")]
mod env_scene;
mod error;
mod frame;
mod geom;
mod plot;
mod records;
mod renderer;
mod scene;
mod terrain;
mod text;
mod writer;

pub use camera::{Camera, CameraConfig, NEAR_PLANE_M, REFERENCE_DISTANCE_M, REFERENCE_HEIGHT_M};
#[cfg(feature = "env")]
pub use env_scene::env_scene;
pub use error::{PlotError, RenderError, WriteError};
pub use frame::Frame;
/// A record's reward terms by name (hyq-spec's type, which [`PlotRecord::terms`] holds).
pub use hyq_spec::TermValues;
pub use plot::{
    DISTANCE_PLOT_SIZE, EpisodePlots, JsonlPlots, PlotOptions, REGULARIZER_PLOT_CELL,
    REWARD_PLOT_SIZE, plot_distance, plot_episode, plot_jsonl, plot_records, plot_regularizers,
    plot_reward_terms, plot_velocity_terms, reward_plot_legend,
};
pub use records::{
    EpisodeSeries, JsonlRecords, MAX_RECORD_LINE_BYTES, PlotRecord, VELOCITY_COMMAND_COLUMNS,
    VELOCITY_MEASURED_COLUMNS, VelocityPlotRecord, cumulative, parse_jsonl, read_jsonl,
    split_episodes,
};
pub use renderer::{
    DEFAULT_HEIGHT_PX, DEFAULT_WIDTH_PX, MAX_SIDE_PX, MIN_SIDE_PX, RenderConfig, Renderer,
};
pub use scene::{Overlay, RobotPose, Scene, VelocityHud};
pub use text::{SANS, SANS_BOLD};
pub use writer::{
    GIF_MAX_FPS, GIF_MAX_SIDE_PX, GifWriter, PngSequence, encode_png, gif_delay_cs, write_gif,
    write_png, write_png_sequence,
};
