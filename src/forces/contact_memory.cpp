#include "forces/contact_memory.hpp"

#include <algorithm>

namespace tem {

void renumber_records(const std::vector<int>& map, std::vector<MemoryRecord>& records) {
  std::erase_if(records, [&](const MemoryRecord& r) { return pair_gone(map, r.body_a, r.body_b); });
  for (MemoryRecord& r : records) renumber_pair(map, r.body_a, r.body_b);
}

}  // namespace tem
