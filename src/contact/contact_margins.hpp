// How far ahead of overlap each body makes contact (contact.margin, block_manifold.hpp).
//
// Every body gets a reach: a pair of bodies makes contact points once its gap is below the sum
// of their reaches, a body and a wall once the gap is below twice the body's reach (a wall does
// not move). Broad-phase bounds grow by the reach, so the pairs within it are found.
//
// The default ("auto") is what a user never has to touch: the reach covers twice the body's
// motion in the coming step, 2 (|v| + |omega| size) dt + |g| dt^2, plus a floor of 0.5% of the
// body's size (so that a body at rest on another keeps its contact). Twice, because a contact
// that arrives fast brakes one step ahead (semm.cpp, normal_targets). A body that moves farther
// in one step than its reach covers (a kick from an impact that more than doubled its speed)
// may arrive overlapping; the step counts such bodies (outran_margin) and
// `tem run` reports them. A number fixes the pair margin instead (reach = margin / 2 for every
// body; a wall's margin is then the number too); 0 turns contact before overlap off: contacts
// then exist only once blocks overlap, as in the paper.
#pragma once

#include <vector>

#include "world/model.hpp"

namespace tem {

// Whether the scene makes contact before overlap: default SEMM (face normals, corner points)
// with a margin that is "auto" or positive. Paper mode and the penalty model never do: the
// penalty force is a function of the overlap, and paper mode reproduces the paper.
// Inline: the scene reader asks it too (contact.substeps), and links without the contact code.
inline bool contact_before_overlap(const SceneDef& scene) {
  const ContactDef& c = scene.contact;
  return c.model == ContactModel::semm && c.normals == PatchNormals::faces &&
         c.points == PatchPoints::corners && scene.integrator == IntegratorKind::default_ &&
         !(c.margin && *c.margin == 0);
}

// Per body, the reach at `state` (empty when the scene does not make contact before overlap).
void contact_reaches(const Model& model, const State& state, std::vector<Real>& reach,
                     const ExternalLoads* loads = nullptr, const BodySubset* subset = nullptr);

// How many moving bodies moved farther from `before` to `after` (any node of theirs) than their
// reach covered.
int bodies_outrunning_reach(const Model& model, const std::vector<Real>& reach,
                            const std::vector<BodyState>& before,
                            const std::vector<BodyState>& after);

}  // namespace tem
