#include "peridot/parallel/partition.hpp"

#include <string>

#include <zoltan.h>

#include "peridot/core/error.hpp"

namespace peridot {

namespace {

struct Slice {
  const Discretization* disc;
  std::size_t begin, end;
  const std::vector<std::uint64_t>* weight;
  const std::vector<std::uint32_t>* global_id;  ///< of point begin + k
};

int count_objects(void* data, int* ierr) {
  const Slice& s = *static_cast<Slice*>(data);
  *ierr = ZOLTAN_OK;
  return static_cast<int>(s.end - s.begin);
}

void list_objects(void* data, int, int, ZOLTAN_ID_PTR global_ids, ZOLTAN_ID_PTR local_ids, int weight_dim,
                  float* weights, int* ierr) {
  const Slice& s = *static_cast<Slice*>(data);
  for (std::size_t k = 0; k < s.end - s.begin; ++k) {
    global_ids[k] = static_cast<ZOLTAN_ID_TYPE>((*s.global_id)[s.begin + k]);
    local_ids[k] = static_cast<ZOLTAN_ID_TYPE>(k);
    // A point with no bond still costs its integration: weight at least 1.
    if (weight_dim == 1) weights[k] = static_cast<float>(std::max<std::uint64_t>(1, (*s.weight)[k]));
  }
  *ierr = ZOLTAN_OK;
}

int geometry_dimension(void* data, int* ierr) {
  *ierr = ZOLTAN_OK;
  return static_cast<Slice*>(data)->disc->dimension;
}

void geometry(void* data, int, int, int count, ZOLTAN_ID_PTR, ZOLTAN_ID_PTR local_ids, int dim, double* out,
              int* ierr) {
  const Slice& s = *static_cast<Slice*>(data);
  for (int k = 0; k < count; ++k)
    for (int d = 0; d < dim; ++d) out[k * dim + d] = s.disc->x(s.begin + local_ids[k], d);
  *ierr = ZOLTAN_OK;
}

/// The part Zoltan gives each point of the slice (collective).
std::vector<int> partition_slice(const Communicator& comm, Slice& slice, PartitionMethod method) {
  PERIDOT_REQUIRE(slice.weight->size() == slice.end - slice.begin, "one weight per point of the slice");
  float version = 0;
  Zoltan_Initialize(0, nullptr, &version);
  Zoltan_Struct* zz = Zoltan_Create(comm.mpi());
  const char* methods[] = {"RCB", "RIB", "HSFC"};
  for (auto [key, value] : {std::pair{"DEBUG_LEVEL", "0"}, {"LB_METHOD", methods[static_cast<int>(method)]}, {"NUM_GID_ENTRIES", "1"},
                            {"NUM_LID_ENTRIES", "1"}, {"OBJ_WEIGHT_DIM", "1"}, {"RETURN_LISTS", "PARTS"},
                            {"IMBALANCE_TOL", "1.01"}, {"DETERMINISTIC", "1"}})
    Zoltan_Set_Param(zz, key, value);
  Zoltan_Set_Num_Obj_Fn(zz, count_objects, &slice);
  Zoltan_Set_Obj_List_Fn(zz, list_objects, &slice);
  Zoltan_Set_Num_Geom_Fn(zz, geometry_dimension, &slice);
  Zoltan_Set_Geom_Multi_Fn(zz, geometry, &slice);

  int changes = 0, gid_entries = 0, lid_entries = 0, imports = 0, exports = 0;
  ZOLTAN_ID_PTR import_gids = nullptr, import_lids = nullptr, export_gids = nullptr, export_lids = nullptr;
  int *import_procs = nullptr, *import_parts = nullptr, *export_procs = nullptr, *export_parts = nullptr;
  const int status = Zoltan_LB_Partition(zz, &changes, &gid_entries, &lid_entries, &imports, &import_gids, &import_lids,
                                         &import_procs, &import_parts, &exports, &export_gids, &export_lids,
                                         &export_procs, &export_parts);
  PERIDOT_REQUIRE(status == ZOLTAN_OK, "Zoltan's partition failed (status " + std::to_string(status) + ")");
  // RETURN_LISTS = PARTS: the export lists name the part of every object of the slice.
  std::vector<int> slice_owner(slice.end - slice.begin, comm.rank());
  for (int k = 0; k < exports; ++k) slice_owner[export_lids[k]] = export_parts[k];
  Zoltan_LB_Free_Part(&import_gids, &import_lids, &import_procs, &import_parts);
  Zoltan_LB_Free_Part(&export_gids, &export_lids, &export_procs, &export_parts);
  Zoltan_Destroy(&zz);
  return slice_owner;
}

}  // namespace

std::vector<int> partition_points(const Communicator& comm, const Discretization& points,
                                        const std::vector<std::uint32_t>& global_id,
                                        const std::vector<std::uint64_t>& weight, PartitionMethod method) {
  if (comm.serial()) return std::vector<int>(points.num_points(), 0);
  // Fewer points than ranks: nothing to balance, and Zoltan's RCB can fail on it (status −2 for one point on
  // two ranks, or two on four); each point stays with the rank that made it.
  if (comm.sum(static_cast<std::uint64_t>(points.num_points())) < static_cast<std::uint64_t>(comm.size()))
    return std::vector<int>(points.num_points(), comm.rank());
  Slice slice{&points, 0, points.num_points(), &weight, &global_id};
  return partition_slice(comm, slice, method);
}

}  // namespace peridot
