// The force model's contact memory (forces/contact_memory.hpp) as it travels between ranks:
// each record with its body A, and gathered into one process's order.
#pragma once

#include <vector>

#include "distributed/messages.hpp"
#include "forces/contact_memory.hpp"

namespace tem::distributed {

void pack(Packer& out, const MemoryRecord& record);
MemoryRecord unpack_memory_record(Unpacker& in);

// Stable sort into one process's order (pair_key, contact_patch.hpp): records with the same key
// come from one rank, in its order.
void sort_records(std::vector<MemoryRecord>& records);

}  // namespace tem::distributed
