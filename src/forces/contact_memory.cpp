#include "forces/contact_memory.hpp"

#include <algorithm>

namespace tem {

void renumber_records(const std::vector<int>& map, std::vector<MemoryRecord>& records) {
  std::erase_if(records, [&](const MemoryRecord& r) {
    return map[r.body_a] < 0 || (r.body_b >= 0 && map[r.body_b] < 0);
  });
  for (MemoryRecord& r : records) {
    r.body_a = map[r.body_a];
    if (r.body_b >= 0) r.body_b = map[r.body_b];
  }
}

}  // namespace tem
