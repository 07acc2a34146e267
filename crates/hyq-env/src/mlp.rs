//! A learned policy replayed without Python: a multilayer perceptron (the actor of a trained
//! agent, with the observation normalisation it was trained behind) read from a
//! [safetensors](https://huggingface.co/docs/safetensors) file, evaluated in plain Rust.
//!
//! # The file (`hyq-mlp-policy`, version 1)
//!
//! Tensors, for a robot with `n` observation rows and `m` action values:
//!
//! | name | dtype | shape | meaning |
//! |---|---|---|---|
//! | `obs_mean` | F64 | [n] | the running mean of each observation row |
//! | `obs_var` | F64 | [n] | its running variance |
//! | `layers.<k>.weight` | F32 | [out_k, in_k] | layer k's weights, k = 0, 1, …; in_0 = n, in_{k+1} = out_k |
//! | `layers.<k>.bias` | F32 | [out_k] | layer k's bias; the last layer has out = m |
//!
//! Metadata (strings): `format` = `hyq-mlp-policy`, `format_version` = `1`, `robot` (the
//! profile's name), `observation` and `action` (JSON arrays of the observation row names and
//! the joint names, in order), `action_mode` and, for `offset` and `delta`, `action_scale_rad`
//! (`max_offset_rad` or `max_delta_rad`), `activation` (`tanh`, `relu` or `elu`), `obs_clip`
//! and `obs_epsilon`, and `env_config`: a JSON object of dotted configuration keys to TOML
//! values (`{"action.mode": "\"offset\"", "task.fall_penalty": "10.0"}`), the environment the
//! policy was trained in, which front ends apply unless the user sets a key. Other keys
//! (`training_commit`, `trainer`, …) are kept and shown, not interpreted.
//!
//! # The forward pass
//!
//! As Stable-Baselines3's `VecNormalize` and `MlpPolicy` compute it, deterministically:
//!
//! ```text
//! x_i = clip((f32(o_i) − mean_i) / sqrt(var_i + epsilon), −obs_clip, obs_clip)   (then to f32)
//! h   = act(W_k h + b_k) for every layer but the last;  a = W_last h + b_last
//! action_i = clip(a_i, low_i, high_i)   (the action space)
//! ```
//!
//! The observation goes through f32 first because the trainer saw the float32 observations of
//! the Python package; the layers run in f64 on the f32 weights, in a fixed order, so the same
//! observation gives the same action bits on every run and machine, within about 10⁻⁶ of the
//! trainer's float32 arithmetic. A step allocates nothing.

use std::collections::BTreeMap;
use std::path::Path;

use hyq_physics::{RobotModel, input};
use safetensors::{Dtype, SafeTensors};
use thiserror::Error;

use crate::action::ActionSpace;
use crate::config::{ActionMode, EnvConfig, ObservationConfig, ObservationExtra};
use crate::env::observation_layout_for;
use crate::policy::{Policy, PolicyInput};

/// The `format` metadata value of a policy file.
pub const FORMAT: &str = "hyq-mlp-policy";
/// The `format_version` this reader understands.
pub const FORMAT_VERSION: &str = "1";

/// A policy file that cannot be used: which file, and what is wrong with it (one line; what it
/// quotes of the file, such as a metadata string, with control characters escaped).
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("{file}: {}", hyq_physics::printable(.reason))]
pub struct MlpError {
    /// The file (as given), or the source's name.
    pub file: String,
    /// What is wrong.
    pub reason: String,
}

/// The hidden layers' activation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Activation {
    /// tanh(x) (Stable-Baselines3's default for PPO).
    Tanh,
    /// max(0, x).
    Relu,
    /// x for x > 0, e^x − 1 otherwise.
    Elu,
}

impl Activation {
    fn parse(name: &str) -> Option<Self> {
        match name {
            "tanh" => Some(Self::Tanh),
            "relu" => Some(Self::Relu),
            "elu" => Some(Self::Elu),
            _ => None,
        }
    }

    /// The name as written in the file.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Tanh => "tanh",
            Self::Relu => "relu",
            Self::Elu => "elu",
        }
    }

    fn apply(self, x: f64) -> f64 {
        match self {
            Self::Tanh => x.tanh(),
            Self::Relu => x.max(0.0),
            Self::Elu => {
                if x > 0.0 {
                    x
                } else {
                    x.exp_m1()
                }
            }
        }
    }
}

/// What a policy file says about the environment it was trained in.
#[derive(Clone, Debug, PartialEq)]
pub struct MlpMetadata {
    /// The robot profile's name.
    pub robot: String,
    /// The observation rows' names, in order.
    pub observation: Vec<String>,
    /// The joints' names, in action order.
    pub action: Vec<String>,
    /// The action mode.
    pub action_mode: ActionMode,
    /// `max_offset_rad` (`offset`) or `max_delta_rad` (`delta`); `None` for the other modes.
    pub action_scale_rad: Option<f64>,
    /// The configuration it was trained with: dotted keys and TOML values, in key order.
    pub env_config: Vec<(String, String)>,
    /// Every metadata entry, as stored (training commit, trainer, …).
    pub raw: BTreeMap<String, String>,
}

#[derive(Clone, Debug)]
struct Layer {
    inputs: usize,
    outputs: usize,
    /// Row-major [outputs][inputs].
    weight: Vec<f64>,
    bias: Vec<f64>,
}

/// A trained MLP policy (see the module docs).
#[derive(Clone, Debug)]
pub struct MlpPolicy {
    metadata: MlpMetadata,
    activation: Activation,
    obs_mean: Vec<f64>,
    obs_std: Vec<f64>,
    obs_clip: f64,
    layers: Vec<Layer>,
    /// Two scratch vectors as wide as the widest layer.
    scratch: [Vec<f64>; 2],
}

fn mode_name(mode: ActionMode) -> &'static str {
    match mode {
        ActionMode::Normalized => "normalized",
        ActionMode::Absolute => "absolute",
        ActionMode::Delta => "delta",
        ActionMode::Offset => "offset",
    }
}

fn parse_mode(name: &str) -> Option<ActionMode> {
    match name {
        "normalized" => Some(ActionMode::Normalized),
        "absolute" => Some(ActionMode::Absolute),
        "delta" => Some(ActionMode::Delta),
        "offset" => Some(ActionMode::Offset),
        _ => None,
    }
}

/// Makes the error of a policy file from what is wrong with it (the file's name is bound in).
type Fail<'a> = &'a dyn Fn(String) -> MlpError;

/// A policy file's metadata, read and checked.
struct Header {
    metadata: MlpMetadata,
    activation: Activation,
    obs_clip: f64,
    obs_epsilon: f64,
}

impl Header {
    /// Reads the metadata entries `raw` in the order their errors are reported: the format and
    /// its version, the observation and action names, the action mode (and its scale), the
    /// activation, the normaliser's clip and epsilon, the training configuration, the robot.
    fn read(raw: BTreeMap<String, String>, err: Fail<'_>) -> Result<Self, MlpError> {
        let get = |key: &str| entry(&raw, key, err);
        let format = get("format")?;
        if format != FORMAT {
            return Err(err(format!(
                "metadata `format` is {format:?}, expected {FORMAT:?}"
            )));
        }
        let version = get("format_version")?;
        if version != FORMAT_VERSION {
            return Err(err(format!(
                "format version {version:?}, this reader understands {FORMAT_VERSION:?}"
            )));
        }
        let names = |key: &str| -> Result<Vec<String>, MlpError> {
            serde_json::from_str(get(key)?).map_err(|e| {
                err(format!(
                    "metadata `{key}` is not a JSON array of names: {e}"
                ))
            })
        };
        let observation = names("observation")?;
        let action = names("action")?;
        let mode_text = get("action_mode")?;
        let action_mode = parse_mode(mode_text)
            .ok_or_else(|| err(format!("unknown action mode {mode_text:?}")))?;
        let action_scale_rad = action_scale(action_mode, &raw, err)?;
        let activation_text = get("activation")?;
        let activation = Activation::parse(activation_text).ok_or_else(|| {
            err(format!(
                "unknown activation {activation_text:?} (expected tanh, relu or elu)"
            ))
        })?;
        let obs_clip = finite_at_least(&raw, "obs_clip", 0.0, err)?;
        let obs_epsilon = finite_at_least(&raw, "obs_epsilon", 0.0, err)?;
        let env_config: BTreeMap<String, String> = serde_json::from_str(get("env_config")?)
            .map_err(|e| {
                err(format!(
                    "metadata `env_config` is not a JSON object of dotted keys to TOML values: {e}"
                ))
            })?;
        let robot = get("robot")?.to_owned();
        Ok(Self {
            metadata: MlpMetadata {
                robot,
                observation,
                action,
                action_mode,
                action_scale_rad,
                env_config: env_config.into_iter().collect(),
                raw,
            },
            activation,
            obs_clip,
            obs_epsilon,
        })
    }
}

/// The metadata entry `key`, which a policy file must have.
fn entry<'r>(
    raw: &'r BTreeMap<String, String>,
    key: &str,
    err: Fail<'_>,
) -> Result<&'r str, MlpError> {
    raw.get(key).map(String::as_str).ok_or_else(|| {
        err(format!(
            "metadata has no `{key}` entry (not a `{FORMAT}` file)"
        ))
    })
}

/// `action_scale_rad` for the modes that scale the action (`offset`, `delta`): a finite number
/// > 0; `None` for the others, which have no such entry.
fn action_scale(
    mode: ActionMode,
    raw: &BTreeMap<String, String>,
    err: Fail<'_>,
) -> Result<Option<f64>, MlpError> {
    match mode {
        ActionMode::Offset | ActionMode::Delta => {
            let text = entry(raw, "action_scale_rad", err)?;
            let v: f64 = text
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite() && *v > 0.0)
                .ok_or_else(|| {
                    err(format!(
                        "`action_scale_rad` = {text:?} is not a finite number > 0"
                    ))
                })?;
            Ok(Some(v))
        }
        ActionMode::Normalized | ActionMode::Absolute => Ok(None),
    }
}

/// The metadata entry `key` as a finite number ≥ `min`.
fn finite_at_least(
    raw: &BTreeMap<String, String>,
    key: &str,
    min: f64,
    err: Fail<'_>,
) -> Result<f64, MlpError> {
    let text = entry(raw, key, err)?;
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v >= min)
        .ok_or_else(|| err(format!("`{key}` = {text:?} is not a finite number ≥ {min}")))
}

/// The tensor `name` of `dtype` as f64 values with its shape; every value finite.
fn read_tensor(
    tensors: &SafeTensors<'_>,
    name: &str,
    dtype: Dtype,
    err: Fail<'_>,
) -> Result<(Vec<usize>, Vec<f64>), MlpError> {
    let view = tensors
        .tensor(name)
        .map_err(|_| err(format!("has no tensor `{name}`")))?;
    if view.dtype() != dtype {
        return Err(err(format!(
            "tensor `{name}` is {:?}, expected {dtype:?}",
            view.dtype()
        )));
    }
    let data = view.data();
    let values: Vec<f64> = match dtype {
        Dtype::F32 => data
            .chunks_exact(4)
            .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])))
            .collect(),
        _ => data
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect(),
    };
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(err(format!(
            "tensor `{name}` holds a non-finite value ({}) at flat index {i}",
            values[i]
        )));
    }
    Ok((view.shape().to_vec(), values))
}

/// The observation normaliser: the mean and the standard deviation √(var + epsilon) of each of
/// the `n_obs` rows, none of them zero.
fn normaliser(
    tensors: &SafeTensors<'_>,
    n_obs: usize,
    obs_epsilon: f64,
    err: Fail<'_>,
) -> Result<(Vec<f64>, Vec<f64>), MlpError> {
    let (mean_shape, obs_mean) = read_tensor(tensors, "obs_mean", Dtype::F64, err)?;
    let (var_shape, obs_var) = read_tensor(tensors, "obs_var", Dtype::F64, err)?;
    for (name, shape) in [("obs_mean", &mean_shape), ("obs_var", &var_shape)] {
        if shape.as_slice() != [n_obs] {
            return Err(err(format!(
                "tensor `{name}` has shape {shape:?}, expected [{n_obs}] (one per observation row)"
            )));
        }
    }
    if let Some(i) = obs_var.iter().position(|v| *v < 0.0) {
        return Err(err(format!("`obs_var` is negative at row {i}")));
    }
    let obs_std: Vec<f64> = obs_var.iter().map(|v| (v + obs_epsilon).sqrt()).collect();
    if let Some(i) = obs_std.iter().position(|s| *s == 0.0) {
        return Err(err(format!(
            "row {i} has zero variance and epsilon 0: its normalisation divides by zero"
        )));
    }
    Ok((obs_mean, obs_std))
}

/// The layers `layers.0`, `layers.1`, ... until one is missing: each takes the previous one's
/// outputs (the first, the `n_obs` observation rows), and the last gives the `n_act` actions.
fn read_layers(
    tensors: &SafeTensors<'_>,
    n_obs: usize,
    n_act: usize,
    err: Fail<'_>,
) -> Result<Vec<Layer>, MlpError> {
    let mut layers = Vec::new();
    let mut inputs = n_obs;
    loop {
        let k = layers.len();
        let w_name = format!("layers.{k}.weight");
        if tensors.tensor(&w_name).is_err() {
            break;
        }
        let (w_shape, weight) = read_tensor(tensors, &w_name, Dtype::F32, err)?;
        let (b_shape, bias) = read_tensor(tensors, &format!("layers.{k}.bias"), Dtype::F32, err)?;
        if w_shape.len() != 2 || w_shape[1] != inputs {
            return Err(err(format!(
                "tensor `{w_name}` has shape {w_shape:?}, expected [_, {inputs}]"
            )));
        }
        let outputs = w_shape[0];
        if b_shape.as_slice() != [outputs] {
            return Err(err(format!(
                "tensor `layers.{k}.bias` has shape {b_shape:?}, expected [{outputs}]"
            )));
        }
        layers.push(Layer {
            inputs,
            outputs,
            weight,
            bias,
        });
        inputs = outputs;
    }
    if layers.is_empty() {
        return Err(err("has no tensor `layers.0.weight`".into()));
    }
    if inputs != n_act {
        return Err(err(format!(
            "the last layer has {inputs} outputs, the metadata's action layout {n_act}"
        )));
    }
    Ok(layers)
}

impl MlpPolicy {
    /// Reads a policy file of at most hyq-physics' [`input::POLICY`] cap (the capped reader
    /// every user file goes through). Every check that needs only the file is done here: the
    /// format, the metadata, the tensors' shapes and dtypes, and that every number is finite.
    pub fn from_file(path: &Path) -> Result<Self, MlpError> {
        let file = path.display().to_string();
        let bytes = input::read_bytes(path, &input::POLICY).map_err(|e| MlpError {
            file: file.clone(),
            reason: format!("cannot read the policy file: {e}"),
        })?;
        Self::from_bytes(&bytes, &file)
    }

    /// Reads a policy from the bytes of a file; `file` names it in errors. In order: the file's
    /// format, its metadata (`Header::read`), the observation normaliser (`normaliser`) and the
    /// layers (`read_layers`); the first problem found is the error.
    pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Self, MlpError> {
        let err = |reason: String| MlpError {
            file: file.to_owned(),
            reason,
        };
        let (_, header) = SafeTensors::read_metadata(bytes).map_err(|e| {
            err(format!(
                "not a safetensors policy file ({}): expected a `{FORMAT}` file as \
                 examples/export_policy.py writes",
                hyq_physics::one_line(&e.to_string())
            ))
        })?;
        let tensors = SafeTensors::deserialize(bytes).map_err(|e| {
            err(format!(
                "not a valid safetensors file: {}",
                hyq_physics::one_line(&e.to_string())
            ))
        })?;
        let raw: BTreeMap<String, String> = header
            .metadata()
            .clone()
            .unwrap_or_default()
            .into_iter()
            .collect();
        let header = Header::read(raw, &err)?;
        let n_obs = header.metadata.observation.len();
        let (obs_mean, obs_std) = normaliser(&tensors, n_obs, header.obs_epsilon, &err)?;
        let layers = read_layers(&tensors, n_obs, header.metadata.action.len(), &err)?;
        let width = layers
            .iter()
            .map(|l| l.outputs)
            .chain([n_obs])
            .max()
            .unwrap_or(n_obs);
        Ok(Self {
            metadata: header.metadata,
            activation: header.activation,
            obs_mean,
            obs_std,
            obs_clip: header.obs_clip,
            layers,
            scratch: [vec![0.0; width], vec![0.0; width]],
        })
    }

    /// What the file says about its training environment.
    pub fn metadata(&self) -> &MlpMetadata {
        &self.metadata
    }

    /// The hidden layers' activation.
    pub fn activation(&self) -> Activation {
        self.activation
    }

    /// The layer widths, inputs first: `[39, 128, 128, 12]`.
    pub fn widths(&self) -> Vec<usize> {
        std::iter::once(self.layers[0].inputs)
            .chain(self.layers.iter().map(|l| l.outputs))
            .collect()
    }

    /// Checks that an environment of `model` under `config` is the one the policy was trained
    /// for: the robot, the observation rows, the joints and the action mode (with its scale).
    /// `file` names the policy in the error.
    pub fn check_env(
        &self,
        model: &RobotModel,
        config: &EnvConfig,
        file: &str,
    ) -> Result<(), MlpError> {
        let err = |reason: String| MlpError {
            file: file.to_owned(),
            reason,
        };
        let m = &self.metadata;
        if m.robot != model.name() {
            return Err(err(format!(
                "trained for robot {:?}, the environment runs {:?}",
                m.robot,
                model.name()
            )));
        }
        let layout = observation_layout_for(model, config).map_err(|e| err(e.to_string()))?;
        let rows: Vec<&str> = layout.rows().iter().map(|r| r.name.as_ref()).collect();
        if let Some(reason) = layout_mismatch("observation", &m.observation, &rows) {
            return Err(err(reason));
        }
        if let Some(reason) = self.scan_mismatch(&config.observation) {
            return Err(err(reason));
        }
        let joints: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
        if let Some(reason) = layout_mismatch("action", &m.action, &joints) {
            return Err(err(reason));
        }
        let a = &config.action;
        if a.mode != m.action_mode {
            return Err(err(format!(
                "trained with action.mode = {:?}, the environment has {:?}",
                mode_name(m.action_mode),
                mode_name(a.mode)
            )));
        }
        let (key, env_scale) = match a.mode {
            ActionMode::Offset => ("action.max_offset_rad", Some(a.max_offset_rad)),
            ActionMode::Delta => ("action.max_delta_rad", Some(a.max_delta_rad)),
            ActionMode::Normalized | ActionMode::Absolute => ("", None),
        };
        if env_scale != m.action_scale_rad {
            return Err(err(format!(
                "trained with {key} = {:?}, the environment has {:?}",
                m.action_scale_rad.unwrap_or(f64::NAN),
                env_scale.unwrap_or(f64::NAN)
            )));
        }
        Ok(())
    }

    /// Why an environment's height scan is not the one the policy was trained on, if it reads
    /// one: the same row names and count can lie at other points (another extent, another
    /// spacing with the same count), so the scan's geometry is compared too. The trained
    /// geometry is the `observation.height_scan_*` entries of the file's `env_config`, the
    /// defaults for those it does not hold (a trainer writes only the keys it changed).
    fn scan_mismatch(&self, env: &ObservationConfig) -> Option<String> {
        if !env.groups().contains(&ObservationExtra::HeightScan) {
            return None;
        }
        let entries: Vec<(&str, &str)> = self
            .metadata
            .env_config
            .iter()
            .filter(|(k, _)| k.starts_with("observation.height_scan_"))
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect();
        let mut trained = EnvConfig::default();
        if let Err(e) = trained.set_all(&entries) {
            return Some(format!("its env_config's height scan: {e}"));
        }
        let t = &trained.observation;
        [
            (
                "x_m",
                t.height_scan_x_m.to_vec(),
                env.height_scan_x_m.to_vec(),
            ),
            (
                "y_m",
                t.height_scan_y_m.to_vec(),
                env.height_scan_y_m.to_vec(),
            ),
            (
                "spacing_m",
                vec![t.height_scan_spacing_m],
                vec![env.height_scan_spacing_m],
            ),
        ]
        .into_iter()
        .find(|(_, t, e)| t != e)
        .map(|(key, t, e)| {
            let show = |v: &[f64]| match v {
                [one] => format!("{one:?}"),
                many => format!("{many:?}"),
            };
            format!(
                "trained with observation.height_scan_{key} = {}, the environment has {}: the \
                 same scan rows would read the ground at other points",
                show(&t),
                show(&e)
            )
        })
    }

    /// The action for `observation` (one value per observation row), before clipping to the
    /// action space, written into `action` (one per action value). Allocates nothing.
    ///
    /// # Panics
    /// If the slices do not have the policy's lengths.
    pub fn forward(&mut self, observation: &[f64], action: &mut [f64]) {
        assert_eq!(observation.len(), self.obs_mean.len(), "observation length");
        assert_eq!(action.len(), self.metadata.action.len(), "action length");
        let [a, b] = &mut self.scratch;
        for (i, o) in observation.iter().enumerate() {
            // The trainer saw float32 observations and float32 normalised inputs.
            let x = f64::from(*o as f32);
            let z = ((x - self.obs_mean[i]) / self.obs_std[i]).clamp(-self.obs_clip, self.obs_clip);
            a[i] = f64::from(z as f32);
        }
        let (mut input, mut output) = (a, b);
        let last = self.layers.len() - 1;
        for (k, layer) in self.layers.iter().enumerate() {
            for (j, row) in layer.weight.chunks_exact(layer.inputs).enumerate() {
                let mut sum = layer.bias[j];
                for (w, x) in row.iter().zip(&input[..layer.inputs]) {
                    sum += w * x;
                }
                output[j] = if k == last {
                    sum
                } else {
                    self.activation.apply(sum)
                };
            }
            std::mem::swap(&mut input, &mut output);
        }
        action.copy_from_slice(&input[..action.len()]);
    }
}

fn layout_mismatch(what: &str, trained: &[String], env: &[&str]) -> Option<String> {
    if trained.len() != env.len() {
        return Some(format!(
            "trained on {} {what} values, the environment has {}",
            trained.len(),
            env.len()
        ));
    }
    trained.iter().zip(env).position(|(t, e)| t != e).map(|i| {
        format!(
            "{what} value {i} was {:?} in training, the environment's is {:?}",
            trained[i], env[i]
        )
    })
}

impl Policy for MlpPolicy {
    fn name(&self) -> &'static str {
        "mlp"
    }

    fn act(&mut self, input: &PolicyInput<'_>, action: &mut [f64]) {
        self.forward(input.observation, action);
        clip_to_space(action, input.space);
    }
}

fn clip_to_space(action: &mut [f64], space: &ActionSpace) {
    for ((a, lo), hi) in action.iter_mut().zip(space.low()).zip(space.high()) {
        *a = a.clamp(*lo, *hi);
    }
}
