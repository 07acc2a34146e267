// The C++ side of the DART bridge: one `Sim` object owns one DART world.
//
// Only plain data crosses the boundary (the shared structs declared in
// src/bridge.rs, f64 slices). DART and Eigen are hidden behind a pimpl, so
// this header includes neither and the code cxx generates stays small and
// quick to compile.
#pragma once

#include <array>
#include <cstddef>
#include <exception>
#include <memory>

#include "rust/cxx.h"

// cxx turns a C++ exception escaping a `-> Result<..>` bridge function into a
// Rust `Err`. Its default handler catches only `std::exception`; anything else
// (`throw 42`) would terminate the process. This override, picked up by the
// generated code because it is declared before it, catches everything.
namespace rust {
namespace behavior {
template <typename Try, typename Fail>
static void trycatch(Try&& func, Fail&& fail) noexcept try {
  func();
} catch (const std::exception& e) {
  fail(e.what());
} catch (...) {
  fail("unknown C++ exception (not derived from std::exception)");
}
}  // namespace behavior
}  // namespace rust

namespace hyq_dart {

// Shared structs: defined by the code cxx generates from src/bridge.rs.
struct BodyDesc;
struct ShapeDesc;
struct WorldDesc;
struct BaseState;
struct Inertial;
struct Pose;

// One simulated world: the robot skeleton, a static ground box, the
// constraint solver and the collision detector. Not thread-safe; one thread
// at a time may use it (Rust marks it Send but not Sync).
class Sim {
 public:
  struct Impl;
  explicit Sim(std::unique_ptr<Impl> impl);
  ~Sim();
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  // Puts the robot in the given state as if the world had just been built:
  // time, forces, contacts and the collision detector's caches are reset.
  void set_state(const BaseState& base, rust::Slice<const double> q,
                 rust::Slice<const double> qd);
  // Replaces the ground's shape with one height field: `heights` holds
  // `depth` rows of `width` values, `spacing` apart along the shape's x and
  // y, the shape at `pose` in the world. The next set_state builds Bullet's
  // field from it.
  void set_ground_heights(rust::Slice<const float> heights, std::size_t width,
                          std::size_t depth, std::array<double, 2> spacing,
                          const Pose& pose);
  // Puts back the flat ground box.
  void set_ground_flat();
  // Stores the torques of the actuated joints for the next step only.
  void set_joint_torques(rust::Slice<const double> tau);
  // Advances the world by one time step. Returns false when the new state
  // is not finite (or beyond a sanity bound); then nothing but set_state and
  // the joint readouts may be called.
  bool step();

  // Readouts; they cannot fail. Each writes min(out.size(), n) values.
  void joint_positions(rust::Slice<double> out) const;
  void joint_velocities(rust::Slice<double> out) const;
  BaseState base_state() const;
  // World pose of every body frame: x, y, z, qw, qx, qy, qz per body.
  void body_poses(rust::Slice<double> out) const;
  double total_mass() const;

  // Per-episode dynamics (domain randomisation); set_state must follow before
  // the next step. The friction coefficient of every shape, the ground's
  // included.
  void set_friction(double friction);
  // The restitution coefficient of every shape, the ground's included (a
  // contact's is the product of its two shapes').
  void set_restitution(double restitution);
  // A body's mass, centre of mass and inertia (its description frame); the
  // root's frames follow its centre of mass.
  void set_inertial(std::size_t body, const Inertial& inertial);
  Inertial inertial(std::size_t body) const;
  void set_joint_damping(std::size_t joint, double damping);
  // Adds dv (world frame) to the root's linear velocity now: nothing else
  // changes.
  void add_base_velocity(rust::Slice<const double> dv);
  // For each tracked link: did one of its collision shapes touch or
  // penetrate the ground in the contacts the last step's solver used.
  void contacts(rust::Slice<bool> out) const;
  // Number of touching or penetrating contact points in the last step.
  std::size_t num_contacts() const;
  double time() const;

 private:
  std::unique_ptr<Impl> impl_;
};

// Builds a world from a plain-data description. Throws std::invalid_argument
// (naming the body, shape or field) on a bad description and
// std::runtime_error when DART refuses an object.
std::unique_ptr<Sim> new_sim(rust::Slice<const BodyDesc> bodies,
                             rust::Slice<const ShapeDesc> shapes,
                             const WorldDesc& world);

}  // namespace hyq_dart
