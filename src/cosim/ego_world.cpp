#include "relief/cosim/ego_world.h"

#include <BulletDynamics/Vehicle/btRaycastVehicle.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

#include "relief/core/errors.h"
#include "relief/cosim/vehicle_pose.h"

namespace relief {
namespace {

constexpr double kGravity = 9.81;
constexpr double kAirDensity = 1.2;  // kg/m^3
// Collision groups: the scene answers only wheel rays; ego bodies meet only each other.
constexpr int kGroundGroup = 1 << 6;
constexpr int kEgoGroup = 1 << 7;
constexpr int kRayGroup = 1 << 8;
// Where the wheels hang from the body: this far above the box's floor.
constexpr double kConnectionAboveFloor_m = 0.1;

struct ClassRow {
  const char* vclass;
  double mass_kg, power_w, drive_n, brake_n, height_m, wheel_radius_m, drag_area_m2, c_rr;
};
// The vehicle-type table (README, "Ego vehicles"). Powers at the wheels; drive forces the
// gearbox's first-gear limit; brakes about 0.8 g (cars) and 0.5 g (heavy vehicles); drag areas
// c_d A of typical bodies; rolling resistance of car and truck tyres on asphalt.
constexpr ClassRow kClasses[] = {
    {"passenger", 1500.0, 110e3, 6000.0, 12000.0, 1.5, 0.33, 0.7, 0.012},
    {"delivery", 3500.0, 100e3, 12000.0, 25000.0, 2.5, 0.36, 1.8, 0.010},
    {"truck", 20000.0, 240e3, 60000.0, 100000.0, 3.5, 0.5, 6.0, 0.007},
    {"trailer", 40000.0, 330e3, 110000.0, 200000.0, 4.0, 0.5, 6.5, 0.007},
    {"bus", 15000.0, 220e3, 50000.0, 75000.0, 3.2, 0.5, 5.5, 0.008},
    {"coach", 15000.0, 220e3, 50000.0, 75000.0, 3.5, 0.5, 5.0, 0.008},
};

btVector3 bt(const Vec3& v) {
  return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}
Vec3 vec(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

// Wheel rays that see the scene only (never an ego body, its own included).
class GroundRaycaster : public btVehicleRaycaster {
 public:
  explicit GroundRaycaster(btCollisionWorld& world) : world_(world) {}
  void* castRay(const btVector3& from, const btVector3& to, btVehicleRaycasterResult& result) override {
    btCollisionWorld::ClosestRayResultCallback hit(from, to);
    hit.m_collisionFilterGroup = kRayGroup;
    hit.m_collisionFilterMask = kGroundGroup;
    world_.rayTest(from, to, hit);
    if (!hit.hasHit()) return nullptr;
    const btRigidBody* body = btRigidBody::upcast(hit.m_collisionObject);
    if (body == nullptr) return nullptr;
    result.m_hitPointInWorld = hit.m_hitPointWorld;
    result.m_hitNormalInWorld = hit.m_hitNormalWorld.normalized();
    result.m_distFraction = hit.m_closestHitFraction;
    return const_cast<btRigidBody*>(body);  // NOLINT(cppcoreguidelines-pro-type-const-cast): Bullet's API
  }

 private:
  btCollisionWorld& world_;
};

// Height of the body's origin above the ground with the vehicle at rest on level ground: the
// wheels' suspension compressed by the weight (g / (4 k) with Bullet's per-kg stiffness).
double rest_height(const EgoSpec& s) {
  const double compression = kGravity / (4.0 * s.suspension_stiffness);
  return s.wheel_radius_m + s.suspension_rest_m - compression + 0.5 * s.height_m - kConnectionAboveFloor_m;
}

// The height at `at` of the least-squares plane through the contacts (the body's footing;
// their mean lies off the centre where the suspension leans).
double plane_height(const std::array<Vec3, 4>& contacts, const Vec2& at) {
  Eigen::Matrix<double, 4, 3> a;
  Eigen::Vector4d z;
  for (int i = 0; i < 4; ++i) {
    const Vec3& c = contacts[static_cast<std::size_t>(i)];
    a.row(i) << 1.0, c.x() - at.x(), c.y() - at.y();
    z(i) = c.z();
  }
  return a.colPivHouseholderQr().solve(z)(0);
}

}  // namespace

EgoSpec ego_spec_for(const std::string& vclass, double length_m, double width_m, double height_m) {
  const WheelBase wheels = wheel_base_of(length_m, width_m);  // checks the size
  if (!(std::isfinite(height_m) && height_m >= 0.0))
    throw InvalidInput("an ego's height must be a finite number >= 0");
  const ClassRow* row = &kClasses[0];
  for (const ClassRow& r : kClasses)
    if (vclass == r.vclass) row = &r;
  EgoSpec s;
  s.vclass = row->vclass;
  s.mass_kg = row->mass_kg;
  s.engine_power_w = row->power_w;
  s.max_drive_force_n = row->drive_n;
  s.max_brake_force_n = row->brake_n;
  s.wheel_radius_m = row->wheel_radius_m;
  s.drag_area_m2 = row->drag_area_m2;
  s.rolling_resistance = row->c_rr;
  s.length_m = length_m;
  s.width_m = width_m;
  s.height_m = height_m > 0.0 ? height_m : row->height_m;
  s.wheelbase_m = wheels.wheelbase_m;
  s.track_m = wheels.track_m;
  return s;
}

struct EgoWorld::Impl {
  struct Ego {
    EgoSpec spec;
    std::unique_ptr<btBoxShape> shape;
    std::unique_ptr<btDefaultMotionState> motion;
    std::unique_ptr<btRigidBody> body;
    std::unique_ptr<btRaycastVehicle> vehicle;
    EgoControls controls;
  };

  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  GroundRaycaster raycaster{world};
  std::vector<btScalar> vertices;
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> arrays;
  std::unique_ptr<btBvhTriangleMeshShape> ground_shape;
  std::unique_ptr<btRigidBody> ground;
  Vec3 offset = Vec3::Zero();  // scene coordinates minus this are Bullet's
  double substep_s = 0.005;
  std::map<std::string, Ego> egos;  // ordered: the same run steps the same way

  Impl() { world.setGravity(btVector3(0, 0, static_cast<btScalar>(-kGravity))); }
  ~Impl() {
    for (auto& [id, ego] : egos) {
      world.removeAction(ego.vehicle.get());
      world.removeRigidBody(ego.body.get());
    }
    if (ground) world.removeRigidBody(ground.get());
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Ego& at(const std::string& id) {
    const auto it = egos.find(id);
    if (it == egos.end()) throw Error("no ego vehicle '" + id + "' in the physics world");
    return it->second;
  }

  void add_ground(const MeshScene& scene) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const TriangleMesh& m : scene.meshes) {
      if (m.kind == SurfaceKind::marking) continue;
      for (const Vec3& v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    }
    if (!(lo.x() <= hi.x())) throw InvalidInput("the scene has no surface for the ego vehicles to drive on");
    offset = 0.5 * (lo + hi);
    for (const TriangleMesh& m : scene.meshes) {
      if (m.kind == SurfaceKind::marking) continue;
      const int base = static_cast<int>(vertices.size() / 3);
      for (const Vec3& v : m.vertices)
        for (int k = 0; k < 3; ++k) vertices.push_back(static_cast<btScalar>(v[k] - offset[k]));
      for (const auto& t : m.triangles)
        for (const std::uint32_t i : t) indices.push_back(base + static_cast<int>(i));
    }
    arrays = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(indices.size() / 3), indices.data(), 3 * static_cast<int>(sizeof(int)),
        static_cast<int>(vertices.size() / 3), vertices.data(), 3 * static_cast<int>(sizeof(btScalar)));
    ground_shape = std::make_unique<btBvhTriangleMeshShape>(arrays.get(), true);
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, ground_shape.get());
    ground = std::make_unique<btRigidBody>(info);
    world.addRigidBody(ground.get(), kGroundGroup, kRayGroup);
  }

  void add_ego(const std::string& id, const EgoSpec& spec) {
    Ego ego;
    ego.spec = spec;
    ego.shape = std::make_unique<btBoxShape>(btVector3(static_cast<btScalar>(0.5 * spec.width_m),
                                                       static_cast<btScalar>(0.5 * spec.length_m),
                                                       static_cast<btScalar>(0.5 * spec.height_m)));
    btVector3 inertia(0, 0, 0);
    const auto mass = static_cast<btScalar>(spec.mass_kg);
    ego.shape->calculateLocalInertia(mass, inertia);
    ego.motion = std::make_unique<btDefaultMotionState>();
    ego.body = std::make_unique<btRigidBody>(
        btRigidBody::btRigidBodyConstructionInfo(mass, ego.motion.get(), ego.shape.get(), inertia));
    ego.body->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(ego.body.get(), kEgoGroup, kEgoGroup);

    btRaycastVehicle::btVehicleTuning tuning;
    tuning.m_suspensionStiffness = static_cast<btScalar>(spec.suspension_stiffness);
    tuning.m_suspensionCompression = static_cast<btScalar>(spec.suspension_compression);
    tuning.m_suspensionDamping = static_cast<btScalar>(spec.suspension_relaxation);
    tuning.m_maxSuspensionTravelCm = static_cast<btScalar>(100.0 * spec.suspension_travel_m);
    tuning.m_frictionSlip = static_cast<btScalar>(spec.tyre_friction);
    tuning.m_maxSuspensionForce = static_cast<btScalar>(4.0 * spec.mass_kg * kGravity);
    ego.vehicle = std::make_unique<btRaycastVehicle>(tuning, ego.body.get(), &raycaster);
    // x right, z up, y forward; the axles point right so that up x axle is forward and a
    // positive steering value turns left (counter-clockwise about up).
    ego.vehicle->setCoordinateSystem(0, 2, 1);
    const double z = -0.5 * spec.height_m + kConnectionAboveFloor_m;
    for (int w = 0; w < 4; ++w) {
      const bool front = w < 2, left = w % 2 == 0;
      const btVector3 at(static_cast<btScalar>((left ? -0.5 : 0.5) * spec.track_m),
                         static_cast<btScalar>((front ? 0.5 : -0.5) * spec.wheelbase_m),
                         static_cast<btScalar>(z));
      btWheelInfo& wheel = ego.vehicle->addWheel(at, btVector3(0, 0, -1), btVector3(1, 0, 0),
                                                 static_cast<btScalar>(spec.suspension_rest_m),
                                                 static_cast<btScalar>(spec.wheel_radius_m), tuning, front);
      wheel.m_rollInfluence = 0.1F;  // a lower roll moment: the box's centre of mass sits high
    }
    world.addAction(ego.vehicle.get());
    egos.emplace(id, std::move(ego));
  }

  // Rolling resistance and drag against the motion, faded in over the first 0.5 m/s.
  static void apply_resistance(Ego& ego) {
    const btVector3 v = ego.body->getLinearVelocity();
    const double speed = v.length();
    if (speed < 1e-6) return;
    const EgoSpec& s = ego.spec;
    const double up = ego.body->getWorldTransform().getBasis().getColumn(2).z();
    const double rolling =
        ego.vehicle->getNumWheels() > 0 ? s.rolling_resistance * s.mass_kg * kGravity * up : 0.0;
    const double force =
        std::min(1.0, speed / 0.5) * rolling + 0.5 * kAirDensity * s.drag_area_m2 * speed * speed;
    ego.body->applyCentralForce(v * static_cast<btScalar>(-force / speed));
  }

  void apply_controls(Ego& ego) const {
    const EgoControls& c = ego.controls;
    const auto steer =
        static_cast<btScalar>(std::clamp(c.steer_rad, -ego.spec.max_steer_rad, ego.spec.max_steer_rad));
    ego.vehicle->setSteeringValue(steer, 0);
    ego.vehicle->setSteeringValue(steer, 1);
    const auto drive = static_cast<btScalar>(0.5 * std::max(0.0, c.drive_force_n));
    ego.vehicle->applyEngineForce(drive, 2);
    ego.vehicle->applyEngineForce(drive, 3);
    // Bullet's brake is the largest impulse the rolling contact may take per substep.
    const auto brake = static_cast<btScalar>(0.25 * std::max(0.0, c.brake_force_n) * substep_s);
    for (int w = 0; w < 4; ++w) ego.vehicle->setBrake(brake, w);
  }
};

EgoWorld::EgoWorld(const MeshScene& scene, double substep_s) : impl_(std::make_unique<Impl>()) {
  if (!(std::isfinite(substep_s) && substep_s > 0.0 && substep_s <= 0.02))
    throw InvalidInput("the physics substep must be in (0, 0.02] s");
  impl_->substep_s = substep_s;
  impl_->add_ground(scene);
}

EgoWorld::~EgoWorld() = default;

void EgoWorld::place(const std::string& id, const EgoSpec& spec, const Vec2& centre, double heading_rad,
                     double ground_z_m, double speed_mps, double pitch_rad, double roll_rad) {
  if (!impl_->egos.contains(id)) impl_->add_ego(id, spec);
  Impl::Ego& ego = impl_->at(id);
  btTransform pose;
  pose.setIdentity();
  // Yaw about up, then pitch about the body's right axis (x), then roll about its forward axis (y).
  const btQuaternion yaw(btVector3(0, 0, 1), static_cast<btScalar>(heading_rad - 0.5 * std::numbers::pi));
  const btQuaternion pitch(btVector3(1, 0, 0), static_cast<btScalar>(pitch_rad));
  const btQuaternion roll(btVector3(0, 1, 0), static_cast<btScalar>(roll_rad));
  pose.setRotation(yaw * pitch * roll);
  // The body's origin straight above the footing along the body's up axis.
  const btVector3 up = pose.getBasis().getColumn(2);
  pose.setOrigin(bt(Vec3(centre.x(), centre.y(), ground_z_m) - impl_->offset) +
                 up * static_cast<btScalar>(rest_height(ego.spec)));
  ego.body->setWorldTransform(pose);
  ego.motion->setWorldTransform(pose);
  ego.body->setLinearVelocity(pose.getBasis().getColumn(1) * static_cast<btScalar>(speed_mps));
  ego.body->setAngularVelocity(btVector3(0, 0, 0));
  ego.body->clearForces();
  ego.vehicle->resetSuspension();
  for (int w = 0; w < ego.vehicle->getNumWheels(); ++w) {  // contacts where it now stands
    ego.vehicle->updateWheelTransform(w, true);
    ego.vehicle->rayCast(ego.vehicle->getWheelInfo(w));
  }
}

void EgoWorld::remove(const std::string& id) {
  const auto it = impl_->egos.find(id);
  if (it == impl_->egos.end()) return;
  impl_->world.removeAction(it->second.vehicle.get());
  impl_->world.removeRigidBody(it->second.body.get());
  impl_->egos.erase(it);
}

bool EgoWorld::has(const std::string& id) const {
  return impl_->egos.contains(id);
}

void EgoWorld::set_controls(const std::string& id, const EgoControls& controls) {
  impl_->at(id).controls = controls;
}

void EgoWorld::step(double dt_s) {
  const int substeps = std::max(1, static_cast<int>(std::lround(dt_s / impl_->substep_s)));
  for (int i = 0; i < substeps; ++i) {
    for (auto& [id, ego] : impl_->egos) {
      impl_->apply_controls(ego);
      impl_->apply_resistance(ego);
    }
    impl_->world.stepSimulation(static_cast<btScalar>(impl_->substep_s), 0);
  }
}

const EgoSpec& EgoWorld::spec(const std::string& id) const {
  return impl_->at(id).spec;
}

EgoState EgoWorld::state(const std::string& id) const {
  Impl::Ego& ego = impl_->at(id);
  const btTransform& pose = ego.body->getWorldTransform();
  const btMatrix3x3& basis = pose.getBasis();
  const btVector3 forward = basis.getColumn(1), right = basis.getColumn(0);
  EgoState s;
  // The footing's centre: below the body's origin along its up axis, as place() set it.
  const Vec3 origin =
      vec(pose.getOrigin() - basis.getColumn(2) * static_cast<btScalar>(rest_height(ego.spec))) +
      impl_->offset;
  s.centre = Vec2(origin.x(), origin.y());
  s.heading_rad = std::atan2(forward.y(), forward.x());
  s.pitch_rad = std::asin(std::clamp<double>(forward.z(), -1.0, 1.0));
  s.roll_rad = std::asin(std::clamp<double>(-right.z(), -1.0, 1.0));
  s.speed_mps = ego.body->getLinearVelocity().dot(forward);
  for (int w = 0; w < 4; ++w) {
    const btWheelInfo& wheel = ego.vehicle->getWheelInfo(w);
    btVector3 contact = wheel.m_raycastInfo.m_contactPointWS;
    if (wheel.m_raycastInfo.m_isInContact) {
      ++s.wheels_on_ground;
    } else {  // hanging: the wheel's lowest point
      contact = wheel.m_raycastInfo.m_hardPointWS +
                wheel.m_raycastInfo.m_wheelDirectionWS *
                    (wheel.m_raycastInfo.m_suspensionLength + wheel.m_wheelsRadius);
    }
    s.contacts[static_cast<std::size_t>(w)] = vec(contact) + impl_->offset;
  }
  s.ground_z_m = plane_height(s.contacts, s.centre);
  return s;
}

}  // namespace relief
