// What the contact solver asks of the other processes when a run is shared among MPI ranks
// (src/distributed/ implements it; one process passes none). Each contact is solved by one
// rank, but a body touched by contacts of several ranks has a copy on each: the copies follow
// mass splitting (Tonge, Benevolenski and Voroshilov 2012, read for the idea): on each of the
// k ranks whose contacts touch it, the body's copy has k times its inverse mass and inverse
// inertia, and after every sweep the copies take the mean of their velocities. The mean is the
// velocity all the impulses give the body, so at convergence every rank's rows hold at the
// true velocities: the solution of one process, to the solver's tolerance.
#pragma once

#include <vector>

#include "forces/body_response.hpp"
#include "forces/patch_colouring.hpp"

namespace tem {

struct ContactPoint;

class SolverSync {
 public:
  virtual ~SolverSync() = default;
  // Before a solve on these points: finds the bodies their rows share with other ranks and
  // returns `bodies` with those bodies' inverse mass and inverse inertia multiplied by the
  // number of ranks touching them.
  virtual const std::vector<BodyResponse>& split(const std::vector<ContactPoint>& points,
                                                 const std::vector<BodyResponse>& bodies) = 0;
  // The responses split() was given.
  virtual const std::vector<BodyResponse>& unsplit() const = 0;
  // The shared bodies' velocities (slots as the solver's arrays) replaced by their mean over
  // the ranks touching them.
  virtual void average(std::vector<SlotVelocity>& slots) = 0;
  // The sweep size of all ranks (each field's maximum).
  virtual SweepSize largest(const SweepSize& mine) = 0;
  // The sum over all ranks.
  virtual Real sum(Real mine) = 0;
  // Whether `body` is moved by this rank (sums over bodies count each body once).
  virtual bool owns(int body) const = 0;
};

}  // namespace tem
