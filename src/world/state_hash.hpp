// A hash of a State's exact bits, for regression checks (`tem run --hash`): two runs agree on it
// only if every double of every body's state is the same to the last bit.
#pragma once

#include <cstdint>
#include <string>

#include "dynamics/body_state.hpp"

namespace tem {

// FNV-1a over the step count and, per body, x, v, g, Omega and the previous torque.
std::uint64_t state_hash(const State& state);

// 16 lower-case hex digits.
std::string hash_hex(std::uint64_t hash);

}  // namespace tem
