#include "ode_world.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>

namespace tem::ode {
namespace {

// ODE's rotations are 3x4, row-major (the fourth column is padding).
void to_ode(const Mat3& m, dMatrix3 r) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[4 * i + j] = m(i, j);
    r[4 * i + 3] = 0;
  }
}

Mat3 from_ode(const dReal* r) {
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = r[4 * i + j];
  return m;
}

Vec3 from_ode3(const dReal* v) { return Vec3(v[0], v[1], v[2]); }

// A block's hull in ODE's convex format, placed in the body frame by x -> rotation x + offset.
// dCreateConvex keeps pointers to these arrays, so they live as long as the world (in a deque,
// which never moves its elements).
struct ConvexData {
  std::vector<dReal> planes;       // a b c d per face: a x + b y + c z = d, normal outward
  std::vector<dReal> points;       // x y z per node
  std::vector<unsigned> polygons;  // per face: its node count, then its nodes (CCW from outside)
  unsigned plane_count = 0, point_count = 0;
  std::vector<dTriIndex> triangles;  // for a trimesh: three nodes per triangle, CCW from outside
  dTriMeshDataID mesh = nullptr;
};

ConvexData convex_of(const Block& block, const Mat3& rotation, const Vec3& offset) {
  ConvexData c;
  for (const Vec3& node : block.nodes()) {
    const Vec3 p = rotation * node + offset;
    c.points.insert(c.points.end(), {p.x(), p.y(), p.z()});
  }
  for (const Polygon& face : block.polygons()) {
    const Vec3 n = rotation * face.normal;
    c.planes.insert(c.planes.end(), {n.x(), n.y(), n.z(), face.offset + n.dot(offset)});
    c.polygons.push_back(static_cast<unsigned>(face.nodes.size()));
    for (int node : face.nodes) c.polygons.push_back(static_cast<unsigned>(node));
  }
  for (const Triangle& t : block.triangles())
    for (int node : t.nodes) c.triangles.push_back(static_cast<dTriIndex>(node));
  c.plane_count = static_cast<unsigned>(block.polygons().size());
  c.point_count = static_cast<unsigned>(block.nodes().size());
  return c;
}

// What a geom stands for, for the pair's coefficients (dGeomSetData points at one of these).
struct GeomTag {
  int material = 0;
};

// ODE's library-wide state: initialised once per process, closed with the last world.
int ode_users = 0;

}  // namespace

struct OdeWorld::Impl {
  const Model& model;
  OdeSettings settings;
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dBodyID> bodies;  // per Model body; null for a fixed one
  std::vector<BodyState> fixed;  // per Model body: where a fixed one stays
  std::deque<ConvexData> convex;
  std::deque<GeomTag> tags;
  std::vector<dContactGeom> scratch;

  explicit Impl(const Model& m) : model(m) {}

  void contact_pair(dGeomID a, dGeomID b) {
    dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
    if (ba == bb) return;  // blocks of one body, or two static geoms
    // Nothing to solve where neither side can move (disabled means asleep).
    const bool a_moves = ba && dBodyIsEnabled(ba), b_moves = bb && dBodyIsEnabled(bb);
    if (!a_moves && !b_moves) return;
    const int n = dCollide(a, b, settings.max_contacts, scratch.data(), sizeof(dContactGeom));
    if (n <= 0) return;
    const auto* ta = static_cast<const GeomTag*>(dGeomGetData(a));
    const auto* tb = static_cast<const GeomTag*>(dGeomGetData(b));
    const PairCoefficients& pair = model.coefficients(ta->material, tb->material);
    dContact c{};
    c.surface.mode = dContactApprox1;
    c.surface.mu = settings.friction >= 0 ? settings.friction : pair.friction;
    const Real e = settings.restitution >= 0 ? settings.restitution : pair.restitution;
    if (e > 0) {
      c.surface.mode |= dContactBounce;
      c.surface.bounce = e;
      c.surface.bounce_vel = 0;
    }
    for (int i = 0; i < n; ++i) {
      c.geom = scratch[i];
      dJointAttach(dJointCreateContact(world, contacts, &c), ba, bb);
    }
  }

  static void near_callback(void* data, dGeomID a, dGeomID b) {
    static_cast<Impl*>(data)->contact_pair(a, b);
  }
};

OdeWorld::OdeWorld(const Model& model, const State& initial, const OdeSettings& settings)
    : impl_(std::make_unique<Impl>(model)) {
  if (ode_users++ == 0) dInitODE2(0);
  // The headers say double; a library built otherwise would misread every number.
  if (!dCheckConfiguration("ODE_double_precision"))
    throw std::runtime_error("the ODE library is not built in double precision");
  Impl& w = *impl_;
  w.settings = settings;
  w.scratch.resize(static_cast<size_t>(std::max(1, settings.max_contacts)));
  w.world = dWorldCreate();
  w.space = dHashSpaceCreate(nullptr);
  w.contacts = dJointGroupCreate(0);
  const Vec3& gravity = model.scene.gravity;
  dWorldSetGravity(w.world, gravity.x(), gravity.y(), gravity.z());
  dWorldSetERP(w.world, settings.erp);
  dWorldSetCFM(w.world, settings.cfm);
  dWorldSetContactSurfaceLayer(w.world, settings.surface_layer);
  dWorldSetQuickStepNumIterations(w.world, settings.iterations);
  dWorldSetAutoDisableFlag(w.world, settings.sleeping ? 1 : 0);

  // Hash cells from about the smallest body's extent to twice the largest's (2^level each).
  Real smallest = INFINITY, largest = 0;
  for (int i = 0; i < static_cast<int>(model.bodies.size()); ++i) {
    const Real size = body_size(model, i);
    smallest = std::min(smallest, size);
    largest = std::max(largest, size);
  }
  if (largest > 0) {
    const int low = static_cast<int>(std::floor(std::log2(smallest)));
    const int high = std::max(low + 1, static_cast<int>(std::ceil(std::log2(4 * largest))));
    dHashSpaceSetLevels(w.space, low, high);
  }

  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& body = model.bodies[i];
    const BodyState& s = initial.bodies[i];
    dMatrix3 attitude;
    to_ode(s.g, attitude);
    dBodyID b = nullptr;
    if (!body.fixed) {
      b = dBodyCreate(w.world);
      dMass mass;
      const Mat3& a = body.inertia.inertia;  // body axes, about the centre of mass (the origin)
      dMassSetParameters(&mass, body.inertia.mass, 0, 0, 0, a(0, 0), a(1, 1), a(2, 2), a(0, 1),
                         a(0, 2), a(1, 2));
      dBodySetMass(b, &mass);
      dBodySetPosition(b, s.x.x(), s.x.y(), s.x.z());
      dBodySetRotation(b, attitude);
      dBodySetLinearVel(b, s.v.x(), s.v.y(), s.v.z());
      const Vec3 omega = s.angular_velocity_world();  // ODE's is in world axes
      dBodySetAngularVel(b, omega.x(), omega.y(), omega.z());
    }
    w.bodies.push_back(b);
    w.fixed.push_back(body.fixed ? s : BodyState{});
    w.tags.push_back(GeomTag{body.material});
    for (const BlockInstance& inst : body.blocks) {
      w.convex.push_back(convex_of(model.blocks[inst.block], inst.rotation, inst.offset));
      ConvexData& c = w.convex.back();
      dGeomID g = nullptr;
      if (settings.trimesh) {
        c.mesh = dGeomTriMeshDataCreate();
        dGeomTriMeshDataBuildDouble(c.mesh, c.points.data(), 3 * sizeof(dReal),
                                    static_cast<int>(c.point_count), c.triangles.data(),
                                    static_cast<int>(c.triangles.size()), 3 * sizeof(dTriIndex));
        g = dCreateTriMesh(w.space, c.mesh, nullptr, nullptr, nullptr);
      } else {
        g = dCreateConvex(w.space, c.planes.data(), c.plane_count, c.points.data(),
                          c.point_count, c.polygons.data());
      }
      dGeomSetData(g, &w.tags.back());
      if (b) {
        dGeomSetBody(g, b);
      } else {  // a static geom where the fixed body stands
        dGeomSetPosition(g, s.x.x(), s.x.y(), s.x.z());
        dGeomSetRotation(g, attitude);
      }
    }
  }

  // Walls: static half-spaces n . x >= n . point, n into the space where bodies live.
  for (const Wall& wall : model.walls) {
    w.tags.push_back(GeomTag{wall.material});
    dGeomID g = dCreatePlane(w.space, wall.normal.x(), wall.normal.y(), wall.normal.z(),
                             wall.normal.dot(wall.point));
    dGeomSetData(g, &w.tags.back());
  }
}

OdeWorld::~OdeWorld() {
  Impl& w = *impl_;
  dJointGroupDestroy(w.contacts);
  dSpaceDestroy(w.space);  // and its geoms (the space's cleanup mode is on by default)
  dWorldDestroy(w.world);  // and its bodies
  for (ConvexData& c : w.convex)
    if (c.mesh) dGeomTriMeshDataDestroy(c.mesh);
  if (--ode_users == 0) dCloseODE();
}

void OdeWorld::step(Real dt) {
  Impl& w = *impl_;
  dSpaceCollide(w.space, &w, &Impl::near_callback);
  if (w.settings.quick_step)
    dWorldQuickStep(w.world, dt);
  else
    dWorldStep(w.world, dt);
  dJointGroupEmpty(w.contacts);
}

State OdeWorld::state() const {
  const Impl& w = *impl_;
  State state;
  state.bodies.resize(w.bodies.size());
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    BodyState& s = state.bodies[i];
    dBodyID b = w.bodies[i];
    if (!b) {  // fixed: where it started
      s = w.fixed[i];
      continue;
    }
    s.x = from_ode3(dBodyGetPosition(b));
    s.g = from_ode(dBodyGetRotation(b));
    s.v = from_ode3(dBodyGetLinearVel(b));
    s.omega = s.g.transpose() * from_ode3(dBodyGetAngularVel(b));  // world to body axes
  }
  return state;
}

int OdeWorld::sleeping_bodies() const {
  int n = 0;
  for (dBodyID b : impl_->bodies)
    if (b && !dBodyIsEnabled(b)) ++n;
  return n;
}

}  // namespace tem::ode
