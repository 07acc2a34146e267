// The DART world behind `hyq_dart::Sim`: built from a plain-data robot
// description (not from DART's URDF loader, which drops <capsule>), stepped
// with the Bullet collision detector.
//
// Granular DART headers only: <dart/dart.hpp> needs an extra package and
// triples the compile time of this file.
#include "hyq-dart/include/hyq_dart.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <mutex>
#include <streambuf>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <dart/collision/CollisionObject.hpp>
#include <dart/collision/CollisionResult.hpp>
#include <dart/collision/bullet/BulletCollisionDetector.hpp>
#include <dart/collision/bullet/BulletCollisionObject.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/CapsuleShape.hpp>
#include <dart/dynamics/CylinderShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/HeightmapShape.hpp>
#include <dart/dynamics/Inertia.hpp>
#include <dart/dynamics/RevoluteJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/SphereShape.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include "hyq-dart/src/bridge.rs.h"

// Debian's libdart is compiled for baseline x86-64, where Eigen aligns
// fixed-size objects to 16 bytes. Eigen objects built here with another
// alignment (AVX: 32, AVX-512: 64) and freed inside libdart crash at once
// ("free(): invalid pointer"), so refuse to build that way.
#if defined(__AVX__)
#error "hyq-dart: compile the DART bridge for baseline x86-64 (no -mavx/-march=native): Debian's libdart is built that way and Eigen's alignment must match"
#endif
static_assert(EIGEN_MAX_STATIC_ALIGN_BYTES == 16,
              "hyq-dart: Eigen's static alignment must be 16 bytes to match "
              "Debian's libdart (baseline x86-64); do not build with AVX flags");

namespace hyq_dart {

namespace {

using dart::dynamics::BodyNode;
using dart::dynamics::ShapeNode;

// Coordinates beyond this magnitude (m, rad, m/s, rad/s) count as diverged.
// No sane state comes near it, and it keeps every transform DART computes
// from the coordinates finite.
constexpr double kSaneBound = 1e8;

Eigen::Isometry3d to_isometry(const Pose& pose, const std::string& what) {
  const auto& r = pose.rotation;
  Eigen::Quaterniond quat(r[0], r[1], r[2], r[3]);
  const double norm = quat.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6) {
    throw std::invalid_argument(what + ": rotation quaternion must have unit length, got norm " +
                                std::to_string(norm));
  }
  for (double t : pose.translation) {
    if (!std::isfinite(t)) {
      throw std::invalid_argument(what + ": translation must be finite");
    }
  }
  quat.normalize();
  Eigen::Isometry3d tf = Eigen::Isometry3d::Identity();
  tf.linear() = quat.toRotationMatrix();
  tf.translation() = Eigen::Vector3d(pose.translation[0], pose.translation[1],
                                     pose.translation[2]);
  return tf;
}

void require(bool ok, const std::string& message) {
  if (!ok) {
    throw std::invalid_argument(message);
  }
}

template <typename T>
T* require_ptr(T* ptr, const std::string& what) {
  if (ptr == nullptr) {
    throw std::runtime_error("DART returned a null " + what);
  }
  return ptr;
}

// Makes world x the shape's first friction direction, so that DART's friction
// pyramid for any contact it takes part in lies along world x and y. Without
// it DART builds the directions from the contact normal (the cross product
// with world z), which for a nearly vertical normal points wherever rounding
// tilts it.
void use_world_friction_axes(dart::dynamics::ShapeNode* node) {
  auto* dynamics = node->getDynamicsAspect();
  dynamics->setFirstFrictionDirection(Eigen::Vector3d::UnitX());
  dynamics->setFirstFrictionDirectionFrame(dart::dynamics::Frame::World());
}

bool finite3(const std::array<double, 3>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// A stream buffer that drops everything written to it.
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

// Drops what is written to std::cout while it lives. DART's Bullet detector
// prints a debug line to std::cout every time it builds a height field (at
// every reset), and the project's programs write their own output (tables,
// JSON lines) to standard output. std::cout is one stream for the whole
// process, so the swap happens under a lock shared by every world.
class QuietStdout {
 public:
  QuietStdout() : guard_(lock()), previous_(std::cout.rdbuf(&null_)) {}
  ~QuietStdout() { std::cout.rdbuf(previous_); }
  QuietStdout(const QuietStdout&) = delete;
  QuietStdout& operator=(const QuietStdout&) = delete;

 private:
  static std::mutex& lock() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> guard_;
  NullBuffer null_;
  std::streambuf* previous_;
};

// DART's Bullet detector, except that it splits every cell of a height field
// along the same diagonal. DART asks Bullet to split the cells along
// alternating diagonals, row by row (zigzag); every other engine splits all
// cells alike. This puts back Bullet's plain split (the cell corners (x+1, y)
// to (x, y+1)) on each height field as Bullet's shape is built for it.
class SplitAlikeBulletDetector : public dart::collision::BulletCollisionDetector {
 public:
  static std::shared_ptr<SplitAlikeBulletDetector> create() {
    return std::shared_ptr<SplitAlikeBulletDetector>(new SplitAlikeBulletDetector());
  }

  // How many height fields this detector built and split.
  int fields_split() const { return fields_split_; }

 protected:
  SplitAlikeBulletDetector() = default;

  std::unique_ptr<dart::collision::CollisionObject> createCollisionObject(
      const dart::dynamics::ShapeFrame* frame) override {
    auto object = BulletCollisionDetector::createCollisionObject(frame);
    split_alike(object.get());
    return object;
  }

  void refreshCollisionObject(dart::collision::CollisionObject* object) override {
    BulletCollisionDetector::refreshCollisionObject(object);
    split_alike(object);
  }

 private:
  void split_alike(dart::collision::CollisionObject* object) {
    auto* bullet = dynamic_cast<dart::collision::BulletCollisionObject*>(object);
    if (bullet == nullptr || bullet->getBulletCollisionObject() == nullptr) {
      return;
    }
    btCollisionShape* shape = bullet->getBulletCollisionObject()->getCollisionShape();
    if (shape != nullptr && shape->isCompound()) {
      auto* compound = static_cast<btCompoundShape*>(shape);
      for (int c = 0; c < compound->getNumChildShapes(); ++c) {
        split_if_field(compound->getChildShape(c));
      }
    } else {
      split_if_field(shape);
    }
  }

  void split_if_field(btCollisionShape* shape) {
    if (shape != nullptr && shape->getShapeType() == TERRAIN_SHAPE_PROXYTYPE) {
      static_cast<btHeightfieldTerrainShape*>(shape)->setUseZigzagSubdivision(false);
      ++fields_split_;
    }
  }

  int fields_split_ = 0;
};

}  // namespace

struct Sim::Impl {
  dart::simulation::WorldPtr world;
  dart::dynamics::SkeletonPtr robot;
  dart::dynamics::SkeletonPtr ground;
  // Every body, description order; the first is the root.
  std::vector<BodyNode*> bodies;
  // The root body and its floating joint. DART integrates a free body's
  // motion at its body frame's origin; at an origin away from the centre of
  // mass that bends the centre of mass's straight flight (by millimetres per
  // second for HyQ's trunk). So the root body's frame sits at its centre of
  // mass, `root_com` in the description's root frame, and every pose or
  // velocity of the root crossing the bridge is converted.
  BodyNode* root = nullptr;
  dart::dynamics::FreeJoint* root_joint = nullptr;
  Eigen::Vector3d root_com = Eigen::Vector3d::Zero();
  // Actuated (revolute) joints in the slice order given by BodyDesc::joint_index;
  // the index of each in the skeleton's generalized coordinates.
  std::vector<dart::dynamics::Joint*> actuated;
  // The same joints, typed: the divergence check after every step reads their
  // coordinates in place (getPositionsStatic) instead of through the
  // skeleton's per-coordinate lookup, which cost ~1 % of a step.
  std::vector<const dart::dynamics::RevoluteJoint*> revolute;
  std::vector<std::size_t> actuated_dof;
  // The joints hanging from the root and the shapes on it, each with its frame
  // as described (in the root's description frame): their frames in the root
  // body frame follow the root's centre of mass when set_inertial moves it.
  std::vector<std::pair<dart::dynamics::Joint*, Eigen::Isometry3d>> root_child_joints;
  std::vector<std::pair<ShapeNode*, Eigen::Isometry3d>> root_shapes;
  // Collision shapes that set a contact flag, and the flag they set.
  std::vector<std::pair<const ShapeNode*, std::size_t>> tracked_shapes;
  std::size_t num_tracked = 0;
  // Torques for the next step.
  Eigen::VectorXd torques;
  // Scratch vectors for set_state, sized once.
  Eigen::VectorXd positions;
  Eigen::VectorXd velocities;

  // The ground: a welded body whose one shape is the flat box (top face at
  // the description's ground height) or a height field.
  BodyNode* ground_body = nullptr;
  dart::dynamics::WeldJoint* ground_joint = nullptr;
  double friction = 0.0;
  double restitution = 0.0;
  bool world_friction_axes = false;
  double ground_height = 0.0;
  double ground_half_extent = 0.0;
  // The height field, if the ground is one, and its heights as given.
  // DART's Bullet detector reverses the field's rows (its flipY) every time
  // it builds Bullet's shape from it, in the shape itself; so before each
  // new detector the rows are put back as given, and every detector builds
  // the same field.
  std::shared_ptr<dart::dynamics::HeightmapShapef> heightmap;
  dart::dynamics::HeightmapShapef::HeightField heightmap_rows;

  // Gives the constraint solver a new Bullet detector (one that splits height
  // field cells alike). Bullet keeps contact
  // manifolds and broadphase pairs between steps; a new detector drops them,
  // which set_state needs to be bitwise equal to a freshly built world.
  void install_fresh_detector() {
    if (heightmap) {
      heightmap->getHeightFieldModifiable() = heightmap_rows;
    }
    auto detector = SplitAlikeBulletDetector::create();
    if (!detector) {
      throw std::runtime_error("DART returned a null BulletCollisionDetector");
    }
    if (heightmap) {
      QuietStdout quiet;
      world->getConstraintSolver()->setCollisionDetector(detector);
    } else {
      world->getConstraintSolver()->setCollisionDetector(detector);
    }
    if (heightmap && detector->fields_split() != 1) {
      throw std::runtime_error("DART's Bullet detector built " +
                               std::to_string(detector->fields_split()) +
                               " height fields, expected 1");
    }
  }

  // Gives the ground body its one shape, with the ground's contact settings.
  // The current collision group holds objects that point at the old shape's
  // node; they are dropped first, while that node still exists (the group
  // would otherwise read the freed node when it lets go of them). The next
  // set_state builds a new group with the new shape.
  dart::dynamics::ShapeNode* attach_ground_shape(
      const std::shared_ptr<dart::dynamics::Shape>& shape) {
    if (world) {
      if (auto group = world->getConstraintSolver()->getCollisionGroup()) {
        group->removeShapeFramesOf(ground.get());
      }
    }
    ground_body->removeAllShapeNodes();
    auto* node = ground_body->createShapeNodeWith<dart::dynamics::CollisionAspect,
                                                   dart::dynamics::DynamicsAspect>(shape);
    require_ptr(node, "ground ShapeNode");
    node->getDynamicsAspect()->setFrictionCoeff(friction);
    node->getDynamicsAspect()->setRestitutionCoeff(restitution);
    if (world_friction_axes) {
      use_world_friction_axes(node);
    }
    return node;
  }

  // The flat ground: a box whose top face is the plane z = ground_height.
  void attach_ground_box() {
    const double half = ground_half_extent;
    attach_ground_shape(std::make_shared<dart::dynamics::BoxShape>(
        Eigen::Vector3d(2.0 * half, 2.0 * half, 1.0)));
    Eigen::Isometry3d ground_tf = Eigen::Isometry3d::Identity();
    ground_tf.translation().z() = ground_height - 0.5;  // top face at ground_height
    ground_joint->setTransformFromParentBodyNode(ground_tf);
    heightmap.reset();
  }
};

Sim::Sim(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Sim::~Sim() = default;

// new_sim in phases: the checks, each body with its joint, each shape, the
// ground, the world.
using dart::dynamics::BodyNode;
using dart::dynamics::Joint;
using dart::dynamics::Skeleton;
using dart::dynamics::FreeJoint;
using dart::dynamics::RevoluteJoint;
using dart::dynamics::WeldJoint;
using dart::dynamics::Shape;
using dart::dynamics::ShapeNode;
using dart::dynamics::BoxShape;
using dart::dynamics::SphereShape;
using dart::dynamics::CapsuleShape;
using dart::dynamics::CylinderShape;
using dart::dynamics::CollisionAspect;
using dart::dynamics::DynamicsAspect;
using dart::dynamics::Inertia;

// The world description's checks, each failure naming the field.
static void check_world(const WorldDesc& desc, std::size_t bodies_count) {
  require(desc.dt > 0.0 && std::isfinite(desc.dt),
          "world.dt must be finite and > 0, got " + std::to_string(desc.dt));
  require(finite3(desc.gravity), "world.gravity must be finite");
  require(desc.friction >= 0.0 && std::isfinite(desc.friction),
          "world.friction must be finite and >= 0, got " + std::to_string(desc.friction));
  require(desc.restitution >= 0.0 && desc.restitution <= 1.0,
          "world.restitution must be in [0, 1], got " + std::to_string(desc.restitution));
  require(std::isfinite(desc.ground_height), "world.ground_height must be finite");
  require(desc.ground_half_extent > 0.0 && std::isfinite(desc.ground_half_extent),
          "world.ground_half_extent must be finite and > 0");
  require(bodies_count > 0, "the robot needs at least one body");
}

// A revolute joint and its body under `parent`: limits enforced as hard
// constraints, damping, force actuation, and its actuated slot.
static std::pair<Joint*, BodyNode*> add_revolute(Sim::Impl& impl, const BodyDesc& b,
                                                 BodyNode* parent,
                                                 const BodyNode::Properties& body_props,
                                                 const Eigen::Isometry3d& from_parent,
                                                 const std::string& what, std::size_t num_bodies) {
  Eigen::Vector3d axis(b.axis[0], b.axis[1], b.axis[2]);
  require(std::isfinite(axis.norm()) && std::abs(axis.norm() - 1.0) < 1e-6,
          what + ": axis must have unit length");
  require(std::isfinite(b.lower) && std::isfinite(b.upper) && b.lower < b.upper,
          what + ": limits must be finite with lower < upper, got [" +
              std::to_string(b.lower) + ", " + std::to_string(b.upper) + "]");
  require(b.damping >= 0.0 && std::isfinite(b.damping),
          what + ": damping must be finite and >= 0");
  RevoluteJoint::Properties props;
  props.mName = std::string(b.joint_name);
  props.mAxis = axis;
  props.mT_ParentBodyToJoint =
      from_parent * to_isometry(b.joint_origin, what + " joint origin");
  props.mT_ChildBodyToJoint = Eigen::Isometry3d::Identity();
  auto pair = impl.robot->createJointAndBodyNodePair<RevoluteJoint>(
      parent, props, body_props);
  Joint* joint = require_ptr(pair.first, "RevoluteJoint for " + what);
  joint->setPositionLowerLimit(0, b.lower);
  joint->setPositionUpperLimit(0, b.upper);
  // Position limits are hard constraints, as in rapier's multibody
  // limits. In DART 6.12 the same switch also enforces the velocity
  // limits; the shared actuator already handles those in Rust for every
  // backend, so DART's are lifted to infinity here.
  joint->setVelocityLowerLimit(0, -std::numeric_limits<double>::infinity());
  joint->setVelocityUpperLimit(0, std::numeric_limits<double>::infinity());
  joint->setPositionLimitEnforced(true);
  joint->setDampingCoefficient(0, b.damping);
  joint->setActuatorType(Joint::FORCE);
  if (b.parent == 0) {
    impl.root_child_joints.emplace_back(joint,
                                         to_isometry(b.joint_origin, what + " joint origin"));
  }
  const std::size_t slot = b.joint_index;
  require(slot < num_bodies,
          what + ": joint_index " + std::to_string(slot) + " out of range");
  if (impl.actuated.size() <= slot) {
    impl.actuated.resize(slot + 1, nullptr);
  }
  require(impl.actuated[slot] == nullptr,
          what + ": joint_index " + std::to_string(slot) + " is used twice");
  impl.actuated[slot] = joint;
  return {joint, pair.second};
}

// Adds body `i` of the description and its joint to the robot; `nodes` holds
// the bodies added so far (a parent comes before its children).
static void add_body(Sim::Impl& impl, std::vector<BodyNode*>& nodes, const BodyDesc& b,
                     std::size_t i, std::size_t bodies_count) {
  const std::string name(b.name);
  const std::string joint_name(b.joint_name);
  const std::string what = "body '" + name + "' (joint '" + joint_name + "')";

  require(b.mass > 0.0 && std::isfinite(b.mass),
          what + ": mass must be finite and > 0, got " + std::to_string(b.mass));
  require(finite3(b.com), what + ": centre of mass must be finite");
  for (double v : b.inertia) {
    require(std::isfinite(v), what + ": inertia must be finite");
  }

  BodyNode* parent = nullptr;
  // Frames given in the root's description frame are moved to its body
  // frame, which sits at its centre of mass.
  Eigen::Isometry3d from_parent = Eigen::Isometry3d::Identity();
  if (i == 0) {
    require(b.parent == -1 && b.joint_kind == JointKind::Free,
            what + ": the first body must be the root (parent -1, free joint)");
    impl.root_com = Eigen::Vector3d(b.com[0], b.com[1], b.com[2]);
  } else {
    if (b.parent == 0) {
      from_parent.translation() = -impl.root_com;
    }
    require(b.parent >= 0 && static_cast<std::size_t>(b.parent) < i,
            what + ": parent index " + std::to_string(b.parent) +
                " must name an earlier body");
    require(b.joint_kind != JointKind::Free,
            what + ": only the root body may have a free joint");
    parent = nodes[static_cast<std::size_t>(b.parent)];
  }

  BodyNode::Properties body_props;
  body_props.mName = name;
  BodyNode* node = nullptr;
  Joint* joint = nullptr;
  if (b.joint_kind == JointKind::Free) {
    FreeJoint::Properties props;
    props.mName = joint_name;
    auto pair = impl.robot->createJointAndBodyNodePair<FreeJoint>(
        parent, props, body_props);
    impl.root_joint = require_ptr(pair.first, "FreeJoint for " + what);
    joint = pair.first;
    node = pair.second;
  } else if (b.joint_kind == JointKind::Revolute) {
    std::tie(joint, node) =
        add_revolute(impl, b, parent, body_props, from_parent, what, bodies_count);
  } else if (b.joint_kind == JointKind::Fixed) {
    WeldJoint::Properties props;
    props.mName = joint_name;
    props.mT_ParentBodyToJoint =
        from_parent * to_isometry(b.joint_origin, what + " joint origin");
    props.mT_ChildBodyToJoint = Eigen::Isometry3d::Identity();
    auto pair = impl.robot->createJointAndBodyNodePair<WeldJoint>(
        parent, props, body_props);
    joint = require_ptr(pair.first, "WeldJoint for " + what);
    node = pair.second;
    if (b.parent == 0) {
      impl.root_child_joints.emplace_back(joint,
                                           to_isometry(b.joint_origin, what + " joint origin"));
    }
  } else {
    throw std::invalid_argument(what + ": unknown joint kind");
  }
  require_ptr(node, "BodyNode for " + what);
  require(joint->getName() == joint_name,
          what + ": joint name is not unique (DART renamed it to '" +
              joint->getName() + "')");
  require(node->getName() == name,
          what + ": body name is not unique (DART renamed it to '" +
              node->getName() + "')");

  const auto& in = b.inertia;
  const Eigen::Vector3d com = (i == 0) ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d(b.com[0], b.com[1], b.com[2]);
  node->setInertia(Inertia(b.mass, com.x(), com.y(), com.z(), in[0], in[1], in[2], in[3],
                           in[4], in[5]));
  nodes.push_back(node);
}

// Adds shape `i` of the description to its body, with the world's contact
// settings.
static void add_shape(Sim::Impl& impl, const std::vector<BodyNode*>& nodes, const ShapeDesc& s,
                      std::size_t i, const WorldDesc& desc) {
  const std::string what = "shape " + std::to_string(i);
  require(s.body < nodes.size(),
          what + ": body index " + std::to_string(s.body) + " out of range");
  require(s.tracked >= -1 && s.tracked < static_cast<int>(desc.num_tracked),
          what + ": tracked index " + std::to_string(s.tracked) + " out of range");
  std::shared_ptr<Shape> shape;
  if (s.kind == ShapeKind::Box) {
    require(s.size[0] > 0 && s.size[1] > 0 && s.size[2] > 0 && finite3(s.size),
            what + ": box half extents must be finite and > 0");
    shape = std::make_shared<BoxShape>(
        2.0 * Eigen::Vector3d(s.size[0], s.size[1], s.size[2]));
  } else if (s.kind == ShapeKind::Sphere) {
    require(s.size[0] > 0 && std::isfinite(s.size[0]),
            what + ": sphere radius must be finite and > 0");
    shape = std::make_shared<SphereShape>(s.size[0]);
  } else if (s.kind == ShapeKind::Capsule) {
    require(s.size[0] > 0 && std::isfinite(s.size[0]) && s.size[1] >= 0 &&
                std::isfinite(s.size[1]),
            what + ": capsule radius must be > 0 and half length >= 0");
    // DART's capsule height is the distance between the cap centres.
    shape = std::make_shared<CapsuleShape>(s.size[0], 2.0 * s.size[1]);
  } else if (s.kind == ShapeKind::Cylinder) {
    require(s.size[0] > 0 && std::isfinite(s.size[0]) && s.size[1] > 0 &&
                std::isfinite(s.size[1]),
            what + ": cylinder radius and half length must be finite and > 0");
    shape = std::make_shared<CylinderShape>(s.size[0], 2.0 * s.size[1]);
  } else {
    throw std::invalid_argument(what + ": unknown shape kind");
  }
  ShapeNode* sn = nodes[s.body]->createShapeNodeWith<CollisionAspect, DynamicsAspect>(shape);
  require_ptr(sn, "ShapeNode for " + what);
  Eigen::Isometry3d shape_tf = to_isometry(s.pose, what + " pose");
  if (s.body == 0) {
    impl.root_shapes.emplace_back(sn, shape_tf);
    shape_tf.pretranslate(-impl.root_com);
  }
  sn->setRelativeTransform(shape_tf);
  sn->getDynamicsAspect()->setFrictionCoeff(desc.friction);
  sn->getDynamicsAspect()->setRestitutionCoeff(desc.restitution);
  if (desc.world_friction_axes) {
    use_world_friction_axes(sn);
  }
  if (s.tracked >= 0) {
    impl.tracked_shapes.emplace_back(sn, static_cast<std::size_t>(s.tracked));
  }
}

// The ground skeleton: a fixed box whose top face is z = ground_height.
static void add_ground(Sim::Impl& impl, const WorldDesc& desc) {
  impl.ground = Skeleton::create("ground");
  require_ptr(impl.ground.get(), "ground Skeleton");
  auto ground_pair = impl.ground->createJointAndBodyNodePair<WeldJoint>();
  impl.ground_joint = require_ptr(ground_pair.first, "ground WeldJoint");
  impl.ground_body = require_ptr(ground_pair.second, "ground BodyNode");
  impl.friction = desc.friction;
  impl.restitution = desc.restitution;
  impl.world_friction_axes = desc.world_friction_axes;
  impl.ground_height = desc.ground_height;
  impl.ground_half_extent = desc.ground_half_extent;
  impl.attach_ground_box();
  impl.ground->setMobile(false);
}

// The world holding the robot and the ground, with its own Bullet detector,
// and the buffers of the robot's state and torques.
static void make_world(Sim::Impl& impl, const WorldDesc& desc) {
  impl.world = dart::simulation::World::create("hyq");
  require_ptr(impl.world.get(), "World");
  impl.world->setGravity(Eigen::Vector3d(desc.gravity[0], desc.gravity[1], desc.gravity[2]));
  impl.world->setTimeStep(desc.dt);
  // The world starts with DART's default FCL detector, which would build
  // (and complain about) capsule geometry for every skeleton added; install
  // Bullet first.
  impl.install_fresh_detector();
  impl.world->addSkeleton(impl.robot);
  impl.world->addSkeleton(impl.ground);

  const auto ndofs = impl.robot->getNumDofs();
  impl.torques = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(impl.actuated.size()));
  impl.positions = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ndofs));
  impl.velocities = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ndofs));
}

std::unique_ptr<Sim> new_sim(rust::Slice<const BodyDesc> bodies,
                             rust::Slice<const ShapeDesc> shapes,
                             const WorldDesc& desc) {
  check_world(desc, bodies.size());
  auto impl = std::make_unique<Sim::Impl>();
  impl->num_tracked = desc.num_tracked;
  impl->robot = Skeleton::create("robot");
  require_ptr(impl->robot.get(), "robot Skeleton");

  std::vector<BodyNode*> nodes;
  nodes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    add_body(*impl, nodes, bodies[i], i, bodies.size());
  }
  impl->root = nodes.front();
  impl->bodies = nodes;
  for (std::size_t slot = 0; slot < impl->actuated.size(); ++slot) {
    require(impl->actuated[slot] != nullptr,
            "no revolute joint has joint_index " + std::to_string(slot) +
                " (the slots must be 0..n)");
    impl->actuated_dof.push_back(impl->actuated[slot]->getIndexInSkeleton(0));
    impl->revolute.push_back(require_ptr(
        dynamic_cast<const RevoluteJoint*>(impl->actuated[slot]), "RevoluteJoint"));
  }
  // Only the root's free joint and the revolute joints have coordinates (a
  // fixed joint has none): the divergence check in step reads exactly these.
  require(impl->robot->getNumDofs() == 6 + impl->revolute.size(),
          "the robot's coordinates must be the free root's 6 and one per revolute joint");

  for (std::size_t i = 0; i < shapes.size(); ++i) {
    add_shape(*impl, nodes, shapes[i], i, desc);
  }
  // Only robot-ground pairs are checked (DART's default): the robot's own
  // shapes overlap near the joints by design.
  impl->robot->disableSelfCollisionCheck();

  add_ground(*impl, desc);
  make_world(*impl, desc);

  // Start from the description's zero pose, exactly as set_state would.
  const std::vector<double> zeros(impl->actuated.size(), 0.0);
  BaseState base{};
  base.orientation = {1.0, 0.0, 0.0, 0.0};
  auto sim = std::make_unique<Sim>(std::move(impl));
  sim->set_state(base, rust::Slice<const double>(zeros.data(), zeros.size()),
                 rust::Slice<const double>(zeros.data(), zeros.size()));
  return sim;
}

void Sim::set_state(const BaseState& base, rust::Slice<const double> q,
                    rust::Slice<const double> qd) {
  Impl& s = *impl_;
  const std::size_t n = s.actuated.size();
  if (q.size() != n || qd.size() != n) {
    throw std::invalid_argument("set_state: expected " + std::to_string(n) +
                                " joint positions and velocities, got " +
                                std::to_string(q.size()) + " and " + std::to_string(qd.size()));
  }
  Pose pose{base.position, base.orientation};
  const Eigen::Isometry3d tf = to_isometry(pose, "set_state base pose");
  require(finite3(base.linear_velocity) && finite3(base.angular_velocity),
          "set_state: base velocities must be finite");
  for (std::size_t i = 0; i < n; ++i) {
    require(std::isfinite(q[i]) && std::isfinite(qd[i]),
            "set_state: joint " + std::to_string(i) + " position/velocity must be finite");
  }

  // The free joint's coordinates: [rotation vector, translation] of the root
  // body frame (at the centre of mass) and its body-frame twist [angular;
  // linear].
  Eigen::Isometry3d body_tf = tf;
  body_tf.translate(s.root_com);
  const Eigen::Vector3d w(base.angular_velocity[0], base.angular_velocity[1],
                          base.angular_velocity[2]);
  const Eigen::Vector3d v_origin(base.linear_velocity[0], base.linear_velocity[1],
                                 base.linear_velocity[2]);
  const Eigen::Vector3d v_com = v_origin + w.cross(tf.linear() * s.root_com);
  const Eigen::Matrix3d rt = tf.linear().transpose();
  s.positions.setZero();
  s.velocities.setZero();
  s.positions.head<6>() = dart::dynamics::FreeJoint::convertToPositions(body_tf);
  s.velocities.segment<3>(0) = rt * w;
  s.velocities.segment<3>(3) = rt * v_com;
  for (std::size_t i = 0; i < n; ++i) {
    s.positions[static_cast<Eigen::Index>(s.actuated_dof[i])] = q[i];
    s.velocities[static_cast<Eigen::Index>(s.actuated_dof[i])] = qd[i];
  }

  auto& robot = *s.robot;
  robot.setPositions(s.positions);
  robot.setVelocities(s.velocities);
  robot.resetAccelerations();
  robot.resetGeneralizedForces();
  robot.resetCommands();
  robot.clearExternalForces();
  robot.clearInternalForces();
  robot.clearConstraintImpulses();
  s.torques.setZero();
  s.world->reset();
  s.world->getConstraintSolver()->clearLastCollisionResult();
  s.install_fresh_detector();
}

void Sim::set_ground_heights(rust::Slice<const float> heights, std::size_t width,
                             std::size_t depth, std::array<double, 2> spacing,
                             const Pose& pose) {
  Impl& s = *impl_;
  require(width >= 2 && depth >= 2 && heights.size() == width * depth,
          "ground heights: expected width x depth >= 2 x 2 values, got " +
              std::to_string(heights.size()) + " for " + std::to_string(width) + " x " +
              std::to_string(depth));
  require(std::isfinite(spacing[0]) && spacing[0] > 0.0 && std::isfinite(spacing[1]) &&
              spacing[1] > 0.0,
          "ground heights: the spacing must be finite and > 0");
  const Eigen::Isometry3d tf = to_isometry(pose, "ground heights pose");
  dart::dynamics::HeightmapShapef::HeightField rows(static_cast<Eigen::Index>(depth),
                                                    static_cast<Eigen::Index>(width));
  for (std::size_t r = 0; r < depth; ++r) {
    for (std::size_t c = 0; c < width; ++c) {
      const float h = heights[r * width + c];
      require(std::isfinite(h), "ground heights: a height is not finite");
      rows(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = h;
    }
  }
  auto field = std::make_shared<dart::dynamics::HeightmapShapef>();
  field->setHeightField(rows);
  field->setScale(Eigen::Vector3f(static_cast<float>(spacing[0]),
                                  static_cast<float>(spacing[1]), 1.0f));
  auto* node = s.attach_ground_shape(field);
  node->setRelativeTransform(tf);
  s.ground_joint->setTransformFromParentBodyNode(Eigen::Isometry3d::Identity());
  s.heightmap = field;
  s.heightmap_rows = rows;
}

void Sim::set_ground_flat() { impl_->attach_ground_box(); }

void Sim::set_joint_torques(rust::Slice<const double> tau) {
  Impl& s = *impl_;
  if (tau.size() != s.actuated.size()) {
    throw std::invalid_argument("set_joint_torques: expected " +
                                std::to_string(s.actuated.size()) + " torques, got " +
                                std::to_string(tau.size()));
  }
  for (std::size_t i = 0; i < tau.size(); ++i) {
    s.torques[static_cast<Eigen::Index>(i)] = tau[i];
  }
}

bool Sim::step() {
  Impl& s = *impl_;
  for (std::size_t i = 0; i < s.actuated.size(); ++i) {
    s.actuated[i]->setForce(0, s.torques[static_cast<Eigen::Index>(i)]);
  }
  s.world->step();
  s.torques.setZero();
  // Debian's libdart keeps its assertions: the first time a non-finite
  // configuration is turned into a transform, DART aborts the process. Read
  // the raw coordinates (no transform involved) and report a diverged state
  // before anything computes a transform from it. The coordinates are read in
  // place from each joint (the skeleton's getPositions() returns a fresh
  // vector, and its getPosition(i) is a virtual lookup per coordinate).
  // |v| < kSaneBound is false for NaN and infinity.
  const auto sane = [](double v) { return std::abs(v) < kSaneBound; };
  const Eigen::Vector6d& root_q = s.root_joint->getPositionsStatic();
  const Eigen::Vector6d& root_v = s.root_joint->getVelocitiesStatic();
  for (Eigen::Index i = 0; i < 6; ++i) {
    if (!(sane(root_q[i]) && sane(root_v[i]))) {
      return false;
    }
  }
  for (const auto* joint : s.revolute) {
    if (!(sane(joint->getPositionsStatic()[0]) && sane(joint->getVelocitiesStatic()[0]))) {
      return false;
    }
  }
  return true;
}

void Sim::joint_positions(rust::Slice<double> out) const {
  const std::size_t n = std::min(out.size(), impl_->actuated.size());
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = impl_->actuated[i]->getPosition(0);
  }
}

void Sim::joint_velocities(rust::Slice<double> out) const {
  const std::size_t n = std::min(out.size(), impl_->actuated.size());
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = impl_->actuated[i]->getVelocity(0);
  }
}

BaseState Sim::base_state() const {
  const BodyNode* root = impl_->root;
  Eigen::Isometry3d tf = root->getWorldTransform();
  tf.translate(-impl_->root_com);
  const Eigen::Quaterniond quat(tf.linear());
  const Eigen::Vector3d v = root->getLinearVelocity(Eigen::Vector3d(-impl_->root_com));
  const Eigen::Vector3d w = root->getAngularVelocity();
  BaseState out{};
  out.position = {tf.translation().x(), tf.translation().y(), tf.translation().z()};
  out.orientation = {quat.w(), quat.x(), quat.y(), quat.z()};
  out.linear_velocity = {v.x(), v.y(), v.z()};
  out.angular_velocity = {w.x(), w.y(), w.z()};
  return out;
}

void Sim::body_poses(rust::Slice<double> out) const {
  const std::size_t n = std::min(out.size() / 7, impl_->bodies.size());
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Isometry3d tf = impl_->bodies[i]->getWorldTransform();
    if (i == 0) {
      tf.translate(-impl_->root_com);
    }
    const Eigen::Quaterniond quat(tf.linear());
    double* o = out.data() + 7 * i;
    o[0] = tf.translation().x();
    o[1] = tf.translation().y();
    o[2] = tf.translation().z();
    o[3] = quat.w();
    o[4] = quat.x();
    o[5] = quat.y();
    o[6] = quat.z();
  }
}

double Sim::total_mass() const { return impl_->robot->getMass(); }

void Sim::set_friction(double friction) {
  require(friction >= 0.0 && std::isfinite(friction),
          "set_friction: friction must be finite and >= 0, got " + std::to_string(friction));
  // A ground shape given later (set_ground_heights, set_ground_flat) gets it too.
  impl_->friction = friction;
  // Every shape of every skeleton, the ground's whatever its shape: DART takes
  // the smaller coefficient of a contact's two shapes.
  for (const auto& skeleton : {impl_->robot, impl_->ground}) {
    for (std::size_t b = 0; b < skeleton->getNumBodyNodes(); ++b) {
      BodyNode* node = skeleton->getBodyNode(b);
      for (ShapeNode* shape : node->getShapeNodesWith<dart::dynamics::DynamicsAspect>()) {
        shape->getDynamicsAspect()->setFrictionCoeff(friction);
      }
    }
  }
}

void Sim::set_restitution(double restitution) {
  require(restitution >= 0.0 && restitution <= 1.0,
          "set_restitution: restitution must be in [0, 1], got " + std::to_string(restitution));
  // A ground shape given later (set_ground_heights, set_ground_flat) gets it too.
  impl_->restitution = restitution;
  for (const auto& skeleton : {impl_->robot, impl_->ground}) {
    for (std::size_t b = 0; b < skeleton->getNumBodyNodes(); ++b) {
      BodyNode* node = skeleton->getBodyNode(b);
      for (ShapeNode* shape : node->getShapeNodesWith<dart::dynamics::DynamicsAspect>()) {
        shape->getDynamicsAspect()->setRestitutionCoeff(restitution);
      }
    }
  }
}

void Sim::set_inertial(std::size_t body, const Inertial& in) {
  using dart::dynamics::Inertia;
  Impl& s = *impl_;
  const std::string what = "set_inertial: body " + std::to_string(body);
  require(body < s.bodies.size(), what + " out of range");
  require(in.mass > 0.0 && std::isfinite(in.mass), what + ": mass must be finite and > 0");
  require(finite3(in.com), what + ": centre of mass must be finite");
  for (double v : in.inertia) {
    require(std::isfinite(v), what + ": inertia must be finite");
  }
  Eigen::Vector3d com(in.com[0], in.com[1], in.com[2]);
  if (body == 0) {
    // The root body frame sits at the centre of mass (see Impl): move it, and
    // the frames described in the root's description frame with it, exactly
    // as new_sim places them.
    s.root_com = com;
    Eigen::Isometry3d from_parent = Eigen::Isometry3d::Identity();
    from_parent.translation() = -s.root_com;
    for (const auto& [joint, origin] : s.root_child_joints) {
      joint->setTransformFromParentBodyNode(from_parent * origin);
    }
    for (const auto& [shape, origin] : s.root_shapes) {
      Eigen::Isometry3d tf = origin;
      tf.pretranslate(-s.root_com);
      shape->setRelativeTransform(tf);
    }
    com = Eigen::Vector3d::Zero();
  }
  const auto& i = in.inertia;
  s.bodies[body]->setInertia(
      Inertia(in.mass, com.x(), com.y(), com.z(), i[0], i[1], i[2], i[3], i[4], i[5]));
}

Inertial Sim::inertial(std::size_t body) const {
  Inertial out{};
  if (body >= impl_->bodies.size()) {
    return out;
  }
  const auto& inertia = impl_->bodies[body]->getInertia();
  Eigen::Vector3d com = inertia.getLocalCOM();
  if (body == 0) {
    com += impl_->root_com;
  }
  const Eigen::Matrix3d moment = inertia.getMoment();
  out.mass = inertia.getMass();
  out.com = {com.x(), com.y(), com.z()};
  out.inertia = {moment(0, 0), moment(1, 1), moment(2, 2),
                 moment(0, 1), moment(0, 2), moment(1, 2)};
  return out;
}

void Sim::set_joint_damping(std::size_t joint, double damping) {
  require(joint < impl_->actuated.size(),
          "set_joint_damping: joint " + std::to_string(joint) + " out of range");
  require(damping >= 0.0 && std::isfinite(damping),
          "set_joint_damping: damping must be finite and >= 0");
  impl_->actuated[joint]->setDampingCoefficient(0, damping);
}

void Sim::add_base_velocity(rust::Slice<const double> dv) {
  require(dv.size() == 3, "add_base_velocity: expected 3 values");
  require(std::isfinite(dv[0]) && std::isfinite(dv[1]) && std::isfinite(dv[2]),
          "add_base_velocity: the velocity change must be finite");
  Impl& s = *impl_;
  // The free joint's velocity is the root body's twist in its own axes
  // [angular; linear of the centre of mass]; with the angular part unchanged,
  // every point of the root gains dv.
  const Eigen::Matrix3d rt = s.root->getWorldTransform().linear().transpose();
  Eigen::Vector6d v = s.root_joint->getVelocities();
  v.tail<3>() += rt * Eigen::Vector3d(dv[0], dv[1], dv[2]);
  s.root_joint->setVelocities(v);
}

void Sim::contacts(rust::Slice<bool> out) const {
  for (auto& flag : out) {
    flag = false;
  }
  // Bullet also reports points up to about a millimetre apart (its contact
  // breaking threshold); DART's result keeps them with a negative depth.
  // Only touching or penetrating points count here.
  for (const auto& contact : impl_->world->getLastCollisionResult().getContacts()) {
    if (!(contact.penetrationDepth >= 0.0)) {
      continue;
    }
    for (const auto* object : {contact.collisionObject1, contact.collisionObject2}) {
      const auto* frame = object->getShapeFrame();
      for (const auto& [shape, link] : impl_->tracked_shapes) {
        if (shape == frame && link < out.size()) {
          out[link] = true;
        }
      }
    }
  }
}

std::size_t Sim::num_contacts() const {
  std::size_t n = 0;
  for (const auto& contact : impl_->world->getLastCollisionResult().getContacts()) {
    n += contact.penetrationDepth >= 0.0 ? 1 : 0;
  }
  return n;
}

double Sim::time() const { return impl_->world->getTime(); }

}  // namespace hyq_dart
