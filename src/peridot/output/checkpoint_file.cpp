#include "peridot/output/checkpoint_file.hpp"

#include <fcntl.h>
#include <netcdf.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "peridot/core/error.hpp"

namespace peridot {

namespace {

namespace fs = std::filesystem;

constexpr int format_version = 1;

class Fnv1a {
 public:
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) hash_ = (hash_ ^ p[k]) * 0x100000001b3ULL;
  }
  void add(const std::string& text) {
    add(text.data(), text.size());
    add("", 1);  // a separator: "ab"+"c" and "a"+"bc" differ
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

/// The netCDF calls of one file; the first failure throws with the path, the call and netCDF's reason.
template <class Error>
class NcFile {
 public:
  NcFile(std::string path, std::string verb) : path_(std::move(path)), verb_(std::move(verb)) {}
  ~NcFile() {
    if (id_ >= 0) nc_close(id_);
  }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  void check(int status, const std::string& what) const {
    if (status != NC_NOERR) throw Error("cannot " + verb_ + " checkpoint '" + path_ + "': " + what + ": " + nc_strerror(status));
  }
  [[noreturn]] void fail(const std::string& why) const { throw Error("cannot " + verb_ + " checkpoint '" + path_ + "': " + why); }
  int& id() { return id_; }
  void close() {
    const int id = id_;
    id_ = -1;
    check(nc_close(id), "closing it");
  }
  std::string text_attribute(int var, const char* name) const {
    std::size_t length = 0;
    check(nc_inq_attlen(id_, var, name, &length), std::string("attribute ") + name);
    std::string text(length, '\0');
    check(nc_get_att_text(id_, var, name, text.data()), std::string("attribute ") + name);
    return text;
  }
  template <class T>
  T number_attribute(int var, const char* name, int (*get)(int, int, const char*, T*)) const {
    std::size_t length = 0;
    check(nc_inq_attlen(id_, var, name, &length), std::string("attribute ") + name);
    if (length != 1) fail(std::string("attribute ") + name + " is not one value");
    T value{};
    check(get(id_, var, name, &value), std::string("attribute ") + name);
    return value;
  }

 private:
  std::string path_, verb_;
  int id_ = -1;
};

/// fsync of a file or folder by path (a folder: so that the rename itself is on disk).
void sync_path(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) throw std::runtime_error("cannot open '" + path.string() + "' to flush it: " + std::strerror(errno));
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  // A folder on a file system that cannot sync folders (EINVAL) still holds the renamed file.
  if (status != 0 && !(directory && error == EINVAL))
    throw std::runtime_error("cannot flush '" + path.string() + "' to disk: " + std::strerror(error));
}

}  // namespace

std::uint64_t checkpoint_checksum(const CheckpointData& data) {
  Fnv1a hash;
  hash.add(data.deck);
  hash.add(data.family_size.data(), data.family_size.size() * sizeof(std::uint32_t));
  hash.add(data.point_index.data(), data.point_index.size() * sizeof(std::uint32_t));  // none in a whole file
  hash.add(data.piece_boxes.data(), data.piece_boxes.size() * sizeof(double));           // piece 0 only
  for (const CheckpointArray& array : data.arrays) {
    hash.add(array.name);
    hash.add(array.layout);
    hash.add(&array.width, sizeof array.width);
    hash.add(array.bytes.data(), array.bytes.size());
  }
  return hash.value();
}

void write_checkpoint_file(const std::string& path, const CheckpointData& data) {
  const std::string tmp = path + ".tmp";
  NcFile<std::runtime_error> nc(tmp, "write");
  nc.check(nc_create(tmp.c_str(), NC_CLOBBER | NC_64BIT_DATA, &nc.id()), "creating it");
  const int id = nc.id();
  auto text = [&](int var, const char* name, const std::string& value) {
    nc.check(nc_put_att_text(id, var, name, value.size(), value.data()), std::string("attribute ") + name);
  };
  text(NC_GLOBAL, "title", "peridot checkpoint");
  nc.check(nc_put_att_int(id, NC_GLOBAL, "format_version", NC_INT, 1, &format_version), "attribute format_version");
  text(NC_GLOBAL, "code_version", data.code_version);
  text(NC_GLOBAL, "deck", data.deck);
  nc.check(nc_put_att_double(id, NC_GLOBAL, "time_step", NC_DOUBLE, 1, &data.time_step), "attribute time_step");
  const long long step = data.step;
  nc.check(nc_put_att_longlong(id, NC_GLOBAL, "step", NC_INT64, 1, &step), "attribute step");
  nc.check(nc_put_att_double(id, NC_GLOBAL, "time", NC_DOUBLE, 1, &data.time), "attribute time");
  const unsigned long long checksum = checkpoint_checksum(data);
  nc.check(nc_put_att_ulonglong(id, NC_GLOBAL, "checksum", NC_UINT64, 1, &checksum), "attribute checksum");

  if (!data.point_index.empty() || data.pieces > 1) {
    PERIDOT_REQUIRE(data.point_index.size() == data.family_size.size(), "a checkpoint piece's point_index does not match its points");
    nc.check(nc_put_att_int(id, NC_GLOBAL, "pieces", NC_INT, 1, &data.pieces), "attribute pieces");
    const unsigned long long global = data.global_points;
    nc.check(nc_put_att_ulonglong(id, NC_GLOBAL, "global_points", NC_UINT64, 1, &global), "attribute global_points");
  }
  // A variable of `length` values; netCDF has no empty fixed dimension (length 0 means unlimited), so an empty
  // one (a piece of a rank without points or bonds) is a scalar marked empty.
  int points = -1;  // the dimension family_size and point_index share
  auto define = [&](const std::string& name, nc_type type, std::size_t length) {
    int dim = -1, var = -1;
    if (length == 0) {
      nc.check(nc_def_var(id, name.c_str(), type, 0, nullptr, &var), "variable " + name);
      const int one = 1;
      nc.check(nc_put_att_int(id, var, "empty", NC_INT, 1, &one), "attribute empty of " + name);
      return var;
    }
    const bool per_point = name == "family_size" || name == "point_index";
    if (per_point && points >= 0) dim = points;
    else nc.check(nc_def_dim(id, per_point ? "points" : (name + ".bytes").c_str(), length, &dim), "dimension of " + name);
    if (per_point) points = dim;
    nc.check(nc_def_var(id, name.c_str(), type, 1, &dim, &var), "variable " + name);
    return var;
  };
  const int family = define("family_size", NC_UINT, data.family_size.size());
  const int index = data.point_index.empty() ? -1 : define("point_index", NC_UINT, data.point_index.size());
  const int boxes = data.piece_boxes.empty() ? -1 : define("piece_boxes", NC_DOUBLE, data.piece_boxes.size());
  std::vector<int> vars;
  for (const CheckpointArray& array : data.arrays) {
    const int var = define(array.name, NC_UBYTE, array.bytes.size());
    text(var, "layout", array.layout);
    const unsigned long long width = array.width;
    nc.check(nc_put_att_ulonglong(id, var, "width", NC_UINT64, 1, &width), "attribute width of " + array.name);
    vars.push_back(var);
  }
  nc.check(nc_enddef(id), "its header");
  if (!data.family_size.empty()) nc.check(nc_put_var_uint(id, family, data.family_size.data()), "variable family_size");
  if (index >= 0) nc.check(nc_put_var_uint(id, index, data.point_index.data()), "variable point_index");
  if (boxes >= 0) nc.check(nc_put_var_double(id, boxes, data.piece_boxes.data()), "variable piece_boxes");
  for (std::size_t k = 0; k < vars.size(); ++k)
    if (!data.arrays[k].bytes.empty())
      nc.check(nc_put_var_uchar(id, vars[k], data.arrays[k].bytes.data()), "variable " + data.arrays[k].name);
  nc.close();
  sync_path(tmp, false);
  std::error_code error;
  fs::rename(tmp, path, error);
  if (error) throw std::runtime_error("cannot move checkpoint '" + tmp + "' to '" + path + "': " + error.message());
  const fs::path folder = fs::path(path).parent_path();
  sync_path(folder.empty() ? fs::path(".") : folder, true);
}

CheckpointData read_checkpoint_file(const std::string& path, bool header_only) {
  NcFile<CheckpointFileError> nc(path, "read");
  if (!fs::is_regular_file(path)) nc.fail("no such file");
  nc.check(nc_open(path.c_str(), NC_NOWRITE, &nc.id()), "opening it (not a checkpoint, or truncated)");
  const int id = nc.id();
  if (nc.text_attribute(NC_GLOBAL, "title") != "peridot checkpoint") nc.fail("not a peridot checkpoint");
  const int format = nc.number_attribute<int>(NC_GLOBAL, "format_version", nc_get_att_int);
  if (format != format_version)
    nc.fail("checkpoint format " + std::to_string(format) + "; this peridot reads format " + std::to_string(format_version));
  CheckpointData data;
  data.code_version = nc.text_attribute(NC_GLOBAL, "code_version");
  data.deck = nc.text_attribute(NC_GLOBAL, "deck");
  data.time_step = nc.number_attribute<double>(NC_GLOBAL, "time_step", nc_get_att_double);
  data.step = nc.number_attribute<long long>(NC_GLOBAL, "step", nc_get_att_longlong);
  data.time = nc.number_attribute<double>(NC_GLOBAL, "time", nc_get_att_double);
  const unsigned long long checksum = nc.number_attribute<unsigned long long>(NC_GLOBAL, "checksum", nc_get_att_ulonglong);

  if (nc_inq_att(id, NC_GLOBAL, "pieces", nullptr, nullptr) == NC_NOERR) {
    data.pieces = nc.number_attribute<int>(NC_GLOBAL, "pieces", nc_get_att_int);
    data.global_points = nc.number_attribute<unsigned long long>(NC_GLOBAL, "global_points", nc_get_att_ulonglong);
  }

  int nvars = 0;
  std::size_t points_in_file = 0;
  nc.check(nc_inq_nvars(id, &nvars), "its variables");
  for (int var = 0; var < nvars; ++var) {
    char name[NC_MAX_NAME + 1] = {};
    int ndims = 0, dim = -1;
    nc_type type = NC_NAT;
    nc.check(nc_inq_var(id, var, name, &type, &ndims, nullptr, nullptr), "variable " + std::to_string(var));
    std::size_t length = 0;
    if (ndims == 1) {
      nc.check(nc_inq_vardimid(id, var, &dim), std::string("variable ") + name);
      nc.check(nc_inq_dimlen(id, dim, &length), std::string("variable ") + name);
    } else if (ndims != 0 || nc_inq_att(id, var, "empty", nullptr, nullptr) != NC_NOERR) {
      nc.fail(std::string("variable ") + name + " is not one-dimensional");
    }
    if (header_only && std::string(name) == "family_size") points_in_file = length;
    if (header_only && std::string(name) != "piece_boxes") continue;
    if (std::string(name) == "family_size" || std::string(name) == "point_index") {
      if (type != NC_UINT) nc.fail(std::string(name) + " is not of unsigned integers");
      std::vector<std::uint32_t>& values = std::string(name) == "family_size" ? data.family_size : data.point_index;
      values.resize(length);
      if (length > 0) nc.check(nc_get_var_uint(id, var, values.data()), std::string("variable ") + name);
      continue;
    }
    if (std::string(name) == "piece_boxes") {
      if (type != NC_DOUBLE) nc.fail("piece_boxes is not of doubles");
      data.piece_boxes.resize(length);
      if (length > 0) nc.check(nc_get_var_double(id, var, data.piece_boxes.data()), "variable piece_boxes");
      continue;
    }
    if (type != NC_UBYTE) nc.fail(std::string("variable ") + name + " is not of bytes");
    CheckpointArray array;
    array.name = name;
    array.layout = nc.text_attribute(var, "layout");
    array.width = nc.number_attribute<unsigned long long>(var, "width", nc_get_att_ulonglong);
    array.bytes.resize(length);
    if (length > 0) nc.check(nc_get_var_uchar(id, var, array.bytes.data()), std::string("variable ") + name);
    data.arrays.push_back(std::move(array));
  }
  nc.close();
  if (header_only) {
    if (data.pieces == 1) data.global_points = points_in_file;
    return data;
  }
  if (checkpoint_checksum(data) != checksum) nc.fail("its checksum does not match its contents (the file is corrupt)");
  if (data.pieces == 1) data.global_points = data.family_size.size();
  if (data.pieces > 1 && data.point_index.size() != data.family_size.size()) nc.fail("its point_index does not match its points");
  if (!data.piece_boxes.empty() && data.piece_boxes.size() != 6 * static_cast<std::size_t>(data.pieces))
    nc.fail("its piece_boxes do not match its pieces");
  return data;
}

}  // namespace peridot
