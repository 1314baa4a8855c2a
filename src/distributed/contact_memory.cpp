#include "distributed/contact_memory.hpp"

#include <algorithm>

#include "contact/contact_patch.hpp"

namespace tem::distributed {

void pack(Packer& out, const MemoryRecord& record) {
  out.put(record.body_a);
  out.put(record.body_b);
  out.put(record.wall);
  out.put(static_cast<double>(record.values.size()));
  for (const double v : record.values) out.put(v);
}

MemoryRecord unpack_memory_record(Unpacker& in) {
  MemoryRecord record;
  record.body_a = in.integer();
  record.body_b = in.integer();
  record.wall = in.integer();
  const int count = in.integer();
  record.values.resize(static_cast<size_t>(count));
  for (double& v : record.values) v = in.number();
  return record;
}

void sort_records(std::vector<MemoryRecord>& records) {
  std::stable_sort(records.begin(), records.end(),
                   [](const MemoryRecord& p, const MemoryRecord& q) {
                     return pair_key(p) < pair_key(q);
                   });
}

}  // namespace tem::distributed
