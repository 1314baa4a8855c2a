#include "distributed/rcb_partition.hpp"

#include <zoltan.h>

#include <stdexcept>
#include <string>

namespace tem::distributed {

RcbPartition::RcbPartition(MPI_Comm comm) : input_(std::make_unique<Input>()) {
  MPI_Comm_rank(comm, &rank_);
  float version = 0;
  if (Zoltan_Initialize(0, nullptr, &version) != ZOLTAN_OK)
    throw std::runtime_error("Zoltan_Initialize failed");
  zoltan_ = Zoltan_Create(comm);
  if (!zoltan_) throw std::runtime_error("Zoltan_Create failed");
  auto set = [&](const char* name, const char* value) {
    if (Zoltan_Set_Param(zoltan_, name, value) != ZOLTAN_OK)
      throw std::runtime_error(std::string("Zoltan parameter ") + name + " refused");
  };
  set("DEBUG_LEVEL", "0");
  set("LB_METHOD", "RCB");
  set("NUM_GID_ENTRIES", "1");
  set("NUM_LID_ENTRIES", "1");
  set("OBJ_WEIGHT_DIM", "1");
  set("RETURN_LISTS", "EXPORT");
  set("KEEP_CUTS", "1");     // owner_of between balancings
  set("RCB_REUSE", "1");     // new cuts start from the old ones: few bodies move
  set("AVERAGE_CUTS", "1");  // a cut midway between two bodies, not on one
  set("IMBALANCE_TOL", "1.05");
  set("DETERMINISTIC", "1");

  Input* in = input_.get();
  Zoltan_Set_Num_Obj_Fn(
      zoltan_,
      [](void* data, int* error) {
        *error = ZOLTAN_OK;
        return static_cast<int>(static_cast<Input*>(data)->ids->size());
      },
      in);
  Zoltan_Set_Obj_List_Fn(
      zoltan_,
      [](void* data, int, int, ZOLTAN_ID_PTR global, ZOLTAN_ID_PTR local, int, float* weights,
         int* error) {
        const Input& input = *static_cast<Input*>(data);
        for (size_t i = 0; i < input.ids->size(); ++i) {
          global[i] = static_cast<ZOLTAN_ID_TYPE>((*input.ids)[i]);
          local[i] = static_cast<ZOLTAN_ID_TYPE>(i);
          weights[i] = static_cast<float>((*input.costs)[i]);
        }
        *error = ZOLTAN_OK;
      },
      in);
  Zoltan_Set_Num_Geom_Fn(
      zoltan_,
      [](void*, int* error) {
        *error = ZOLTAN_OK;
        return 3;
      },
      nullptr);
  Zoltan_Set_Geom_Multi_Fn(
      zoltan_,
      [](void* data, int, int, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR local, int, double* xyz,
         int* error) {
        const Input& input = *static_cast<Input*>(data);
        for (int i = 0; i < count; ++i) {
          const Vec3& c = (*input.centres)[local[i]];
          for (int k = 0; k < 3; ++k) xyz[3 * i + k] = c[k];
        }
        *error = ZOLTAN_OK;
      },
      in);
}

RcbPartition::~RcbPartition() { Zoltan_Destroy(&zoltan_); }

std::vector<int> RcbPartition::balance(const std::vector<int>& ids,
                                       const std::vector<Vec3>& centres,
                                       const std::vector<double>& costs) {
  input_->ids = &ids;
  input_->centres = &centres;
  input_->costs = &costs;
  int changes = 0, gid_entries = 0, lid_entries = 0, imports = 0, exports = 0;
  ZOLTAN_ID_PTR import_global = nullptr, import_local = nullptr, export_global = nullptr,
                export_local = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr,
      *export_parts = nullptr;
  const int code =
      Zoltan_LB_Partition(zoltan_, &changes, &gid_entries, &lid_entries, &imports, &import_global,
                          &import_local, &import_procs, &import_parts, &exports, &export_global,
                          &export_local, &export_procs, &export_parts);
  if (code != ZOLTAN_OK) throw std::runtime_error("Zoltan RCB partitioning failed");
  std::vector<int> owner(ids.size(), rank_);
  for (int i = 0; i < exports; ++i) owner[export_local[i]] = export_procs[i];
  Zoltan_LB_Free_Part(&import_global, &import_local, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_global, &export_local, &export_procs, &export_parts);
  input_->ids = nullptr;
  input_->centres = nullptr;
  input_->costs = nullptr;
  return owner;
}

int RcbPartition::owner_of(const Vec3& point) const {
  double xyz[3] = {point.x(), point.y(), point.z()};
  int rank = -1;
  if (Zoltan_LB_Point_Assign(zoltan_, xyz, &rank) != ZOLTAN_OK)
    throw std::runtime_error("Zoltan could not place a point");
  return rank;
}

}  // namespace tem::distributed
