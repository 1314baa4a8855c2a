#include "bullet_world.hpp"

#include <btBulletDynamicsCommon.h>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace tem::bullet {
namespace {

btVector3 to_bt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

btMatrix3x3 to_bt_matrix(const Mat3& m) {
  return btMatrix3x3(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)),  //
                     btScalar(m(1, 0)), btScalar(m(1, 1)), btScalar(m(1, 2)),  //
                     btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
}

Vec3 from_bt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

Mat3 from_bt_matrix(const btMatrix3x3& m) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}

// Bullet wants the inertia as three principal moments in the rigid body's own frame, while TEM's
// body frame (origin at the centre of mass) keeps the scene's axes, in which A is generally full.
// So each Bullet body lives in TEM's principal frame: A = P diag(d) P^T, P a proper rotation
// whose columns are the principal axes in TEM's body frame; the shapes are placed by P^T and
// the Bullet attitude is g P. This is exact (no inertia is lost, unlike keeping the diagonal of
// A), and costs nothing per step.
void principal_axes(const Mat3& inertia, Mat3& p, Vec3& moments) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
  p = eigen.eigenvectors();
  moments = eigen.eigenvalues();
  if (p.determinant() < 0) p.col(2) = -p.col(2);
}

// The convex hull of a block's nodes, each mapped by x -> rotation x + offset. Bullet inflates
// the hull by the margin: contact is declared `margin` outside the true surface.
std::unique_ptr<btConvexHullShape> make_hull(const Block& block, const Mat3& rotation,
                                             const Vec3& offset, Real margin) {
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& node : block.nodes()) hull->addPoint(to_bt(rotation * node + offset), false);
  hull->setMargin(btScalar(margin));
  hull->recalcLocalAabb();
  return hull;
}

}  // namespace

BulletWorld::BulletWorld(const Model& model, const State& initial,
                         const BulletSettings& settings) {
  config_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                     solver_.get(), config_.get());
  world_->setGravity(to_bt(model.scene.gravity));
  // Bullet's split-impulse threshold (-0.04) is a length tuned to its default margin (0.04):
  // penetration shallower than it is removed by Baumgarte feedback, deeper by split impulses.
  // Scaled with the margin so the two keep Bullet's own proportion.
  world_->getSolverInfo().m_splitImpulsePenetrationThreshold = btScalar(-settings.margin);

  // Bullet combines the two sides' coefficients by product (btManifoldResult), so every object
  // gets the square root: the product is then the wanted value for every pair and every wall.
  const btScalar friction = btScalar(std::sqrt(settings.friction));
  const btScalar restitution = btScalar(std::sqrt(settings.restitution));

  body_count_ = static_cast<int>(model.bodies.size());
  for (int i = 0; i < body_count_; ++i) {
    const Body& body = model.bodies[i];
    const BodyState& s = initial.bodies[i];
    Mat3 p;
    Vec3 moments;
    principal_axes(body.inertia.inertia, p, moments);
    principal_.push_back(p);

    // One block: its hull directly, points already in the principal frame (a compound of one
    // child would only add a transform per test). Several: a compound of hulls.
    btCollisionShape* shape = nullptr;
    if (body.blocks.size() == 1) {
      const BlockInstance& b = body.blocks[0];
      shapes_.push_back(make_hull(model.blocks[b.block], p.transpose() * b.rotation,
                                  p.transpose() * b.offset, settings.margin));
      shape = shapes_.back().get();
    } else {
      auto compound = std::make_unique<btCompoundShape>();
      for (const BlockInstance& b : body.blocks) {
        shapes_.push_back(
            make_hull(model.blocks[b.block], Mat3::Identity(), Vec3::Zero(), settings.margin));
        compound->addChildShape(
            btTransform(to_bt_matrix(p.transpose() * b.rotation), to_bt(p.transpose() * b.offset)),
            shapes_.back().get());
      }
      shapes_.push_back(std::move(compound));
      shape = shapes_.back().get();
    }

    const btScalar mass = body.fixed ? btScalar(0) : btScalar(body.inertia.mass);
    const btVector3 local_inertia = body.fixed ? btVector3(0, 0, 0) : to_bt(moments);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, local_inertia);
    info.m_startWorldTransform = btTransform(to_bt_matrix(s.g * p), to_bt(s.x));
    info.m_friction = friction;
    info.m_restitution = restitution;
    auto rigid = std::make_unique<btRigidBody>(info);
    if (!body.fixed) {
      rigid->setLinearVelocity(to_bt(s.v));
      rigid->setAngularVelocity(to_bt(s.angular_velocity_world()));
      if (!settings.sleeping) rigid->setActivationState(DISABLE_DEACTIVATION);
    }
    world_->addRigidBody(rigid.get());
    bodies_.push_back(std::move(rigid));
  }

  // Walls (the container's faces among them): static half-spaces n . x >= n . point.
  for (const Wall& wall : model.walls) {
    shapes_.push_back(std::make_unique<btStaticPlaneShape>(to_bt(wall.normal),
                                                           btScalar(wall.normal.dot(wall.point))));
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
    info.m_friction = friction;
    info.m_restitution = restitution;
    auto rigid = std::make_unique<btRigidBody>(info);
    world_->addRigidBody(rigid.get());
    bodies_.push_back(std::move(rigid));
  }
}

BulletWorld::~BulletWorld() {
  // The world's destructor still visits its objects: take them out while they exist.
  for (auto& body : bodies_) world_->removeRigidBody(body.get());
}

void BulletWorld::step(Real dt) {
  // maxSubSteps = 0: one internal step of exactly dt, no fixed-step accumulator.
  world_->stepSimulation(btScalar(dt), 0);
}

State BulletWorld::state() const {
  State state;
  state.bodies.resize(body_count_);
  for (int i = 0; i < body_count_; ++i) {
    const btTransform& t = bodies_[i]->getWorldTransform();
    BodyState& b = state.bodies[i];
    b.x = from_bt(t.getOrigin());
    b.g = from_bt_matrix(t.getBasis()) * principal_[i].transpose();
    b.v = from_bt(bodies_[i]->getLinearVelocity());
    b.omega = b.g.transpose() * from_bt(bodies_[i]->getAngularVelocity());  // world to body axes
  }
  return state;
}

int BulletWorld::sleeping_bodies() const {
  int n = 0;
  for (int i = 0; i < body_count_; ++i)
    if (!bodies_[i]->isStaticObject() && !bodies_[i]->isActive()) ++n;
  return n;
}

}  // namespace tem::bullet
