// `tem run` over MPI ranks (mpirun -np N tem run SCENE --out DIR): the loop of one rank. Every
// rank loaded the scene (and, resuming, the checkpoint); rank 0 writes the files, which are
// those of a one-process run: rows gathered in body order, contacts in one process's order,
// one checkpoint that resumes at any rank count, with or without MPI. ParaView frames are
// written in pieces, each rank its own bodies and contacts, under one tem.pvd of .pvtu files.
#pragma once

#include <functional>
#include <string>

#include "distributed/domain.hpp"
#include "io/run_output.hpp"

namespace tem::distributed {

struct RunPlan {
  long long total_steps = 0;
  long long every = 1;             // steps between output rows
  long long checkpoint_every = 0;  // steps between checkpoints, 0: none
  std::string checkpoint_file;
  RunOutput* output = nullptr;  // rank 0's files; null on the other ranks
  std::string directory;        // where every rank writes its ParaView pieces
};

enum class RunEnd { finished, stopped, not_finite };

struct RunResult {
  RunEnd end = RunEnd::finished;
  int bad_body = -1;  // RunEnd::not_finite: the first body whose state is not finite
  State whole;        // rank 0: the whole final State
};

// Steps from the current state to plan.total_steps. `stop_requested` is asked on every rank
// each step; the run stops, after a checkpoint, at the first step where any rank says yes.
// `progress` is called on rank 0 after every step.
// Each step is simulation/step_loop.hpp's take_step, with this run's checkpoints, rebalancing,
// ghost exchange and rows as its hooks.
RunResult run_steps(Domain& domain, Model& model, State& state, Workspace& workspace,
                    const RunPlan& plan, const std::function<bool()>& stop_requested,
                    const std::function<void(long long, Real)>& progress);

// The contact models this first distributed engine carries; the others are refused with the
// reason (empty: carried).
std::string unsupported_reason(const SceneDef& scene);

}  // namespace tem::distributed
