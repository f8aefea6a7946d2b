// A thin typed layer over the HDF5 C API, used by io/hdf5_file.cpp only: RAII handles,
// scalar and string attributes, per-particle arrays as datasets, and errors that name the
// file and the object. Include it only where <hdf5.h> may be seen.
#pragma once

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include "solver/state/types.hpp"

namespace swell::hdf5 {

// Datasets written with compression on are chunked and deflated above this many values.
constexpr hsize_t kCompressAbove = 4096;
constexpr hsize_t kChunkValues = 65536;  // 512 KiB of doubles per chunk

// Turns off HDF5's automatic printing of its error stack while alive: every failure becomes
// an exception with our own message (plus HDF5's innermost reason), never console noise.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

inline herr_t keep_innermost(unsigned n, const H5E_error2_t* err, void* out) {
  if (n == 0 && err->desc) *static_cast<std::string*>(out) = err->desc;
  return 0;
}

// The description of the error where HDF5 detected it ("truncated file: eof = ...").
// Must be called right after the failing call, before any other HDF5 call.
inline std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  // A failed system call comes as "file write failed: time = ..., errno = 27, error message =
  // 'File too large', buf = ...": keep its head and the system's message.
  const std::string tag = "error message = '";
  const auto k = reason.find(tag);
  if (k != std::string::npos) {
    const auto end = reason.find('\'', k + tag.size());
    reason = reason.substr(0, reason.find(':')) + ": " +
             reason.substr(k + tag.size(), end == std::string::npos ? end : end - k - tag.size());
  }
  return reason;
}

[[noreturn]] inline void fail(const std::string& file, const std::string& where,
                              const std::string& what) {
  std::string msg = "HDF5 file '" + file + "'";
  if (!where.empty()) msg += ", " + where;
  throw std::runtime_error(msg + ": " + what);
}

[[noreturn]] inline void fail_h5(const std::string& file, const std::string& where,
                                 const std::string& what) {
  const std::string reason = hdf5_reason();
  fail(file, where, reason.empty() ? what : what + " (HDF5: " + reason + ")");
}

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), closer_(o.closer_) {}
  Handle& operator=(Handle&&) = delete;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  hid_t release() { return std::exchange(id_, -1); }
  void reset() {
    if (id_ >= 0) closer_(id_);
    id_ = -1;
  }
  // Closes now and says whether it worked (closing a file writes its cached metadata).
  bool close() { return id_ < 0 || closer_(std::exchange(id_, -1)) >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

// A group (or file root) of an open file, with the names error messages need.
struct Loc {
  hid_t id;
  std::string file;
  std::string path;

  std::string child(const std::string& name) const {
    return path == "/" ? "/" + name : path + "/" + name;
  }
  Loc at(hid_t child_id, const std::string& name) const { return {child_id, file, child(name)}; }
  std::string dataset(const std::string& name) const { return "dataset '" + child(name) + "'"; }
  std::string attribute(const std::string& name) const {
    return "attribute '" + name + "' of '" + path + "'";
  }
};

template <class T>
struct H5Types;
// clang-format off
template <> struct H5Types<double> { static hid_t mem() { return H5T_NATIVE_DOUBLE; } static hid_t file() { return H5T_IEEE_F64LE; } };
template <> struct H5Types<float> { static hid_t mem() { return H5T_NATIVE_FLOAT; } static hid_t file() { return H5T_IEEE_F32LE; } };
template <> struct H5Types<std::int32_t> { static hid_t mem() { return H5T_NATIVE_INT32; } static hid_t file() { return H5T_STD_I32LE; } };
template <> struct H5Types<std::int64_t> { static hid_t mem() { return H5T_NATIVE_INT64; } static hid_t file() { return H5T_STD_I64LE; } };
template <> struct H5Types<std::uint8_t> { static hid_t mem() { return H5T_NATIVE_UINT8; } static hid_t file() { return H5T_STD_U8LE; } };
template <> struct H5Types<std::uint16_t> { static hid_t mem() { return H5T_NATIVE_UINT16; } static hid_t file() { return H5T_STD_U16LE; } };
template <> struct H5Types<std::uint32_t> { static hid_t mem() { return H5T_NATIVE_UINT32; } static hid_t file() { return H5T_STD_U32LE; } };
template <> struct H5Types<std::uint64_t> { static hid_t mem() { return H5T_NATIVE_UINT64; } static hid_t file() { return H5T_STD_U64LE; } };
// clang-format on

inline bool file_exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

inline Handle open_file(const std::string& path, unsigned flags) {
  if (!file_exists(path)) fail(path, "", "does not exist");
  Handle f(H5Fopen(path.c_str(), flags, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) fail_h5(path, "", "cannot be opened: truncated, corrupt or not an HDF5 file");
  return f;
}

inline Handle open_group(const Loc& parent, const std::string& name) {
  Handle g(H5Gopen2(parent.id, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail_h5(parent.file, "group '" + parent.child(name) + "'", "cannot be opened");
  return g;
}

inline Handle create_group(const Loc& parent, const std::string& name) {
  Handle g(H5Gcreate2(parent.id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail_h5(parent.file, "group '" + parent.child(name) + "'", "cannot be created");
  return g;
}

inline bool has_attr(const Loc& g, const char* name) {
  return H5Aexists(g.id, name) > 0;
}

template <class T>
void write_attr(const Loc& g, const char* name, T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(g.id, name, H5Types<T>::file(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (!a.valid() || H5Awrite(a.get(), H5Types<T>::mem(), &value) < 0)
    fail_h5(g.file, g.attribute(name), "cannot be written");
}

template <class T>
T read_attr(const Loc& g, const char* name) {
  if (!has_attr(g, name)) fail(g.file, g.attribute(name), "is missing");
  Handle a(H5Aopen(g.id, name, H5P_DEFAULT), H5Aclose);
  if (!a.valid()) fail_h5(g.file, g.attribute(name), "cannot be opened");
  Handle space(H5Aget_space(a.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    fail(g.file, g.attribute(name), "is not a single value");
  T value{};
  if (H5Aread(a.get(), H5Types<T>::mem(), &value) < 0)
    fail_h5(g.file, g.attribute(name), "cannot be read as a number");
  return value;
}

inline Handle utf8_string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

// Strings are variable-length UTF-8 (h5py reads them as str), in an attribute or a dataset,
// scalar (one string) or 1-D.
inline void write_strings(const Loc& g, const char* name, const std::vector<std::string>& values,
                          bool scalar, bool as_dataset) {
  const std::string where = as_dataset ? g.dataset(name) : g.attribute(name);
  Handle type = utf8_string_type();
  const hsize_t n = values.size();
  Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
  std::vector<const char*> ptrs;
  for (const auto& s : values) ptrs.push_back(s.c_str());
  const hid_t t = type.get(), s = space.get();
  Handle obj =
      as_dataset
          ? Handle(H5Dcreate2(g.id, name, t, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose)
          : Handle(H5Acreate2(g.id, name, t, s, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!obj.valid()) fail_h5(g.file, where, "cannot be created");
  if (n == 0) return;
  const herr_t st = as_dataset ? H5Dwrite(obj.get(), t, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data())
                               : H5Awrite(obj.get(), t, ptrs.data());
  if (st < 0) fail_h5(g.file, where, "cannot be written");
}

std::vector<std::string> read_strings(const Loc& g, const char* name, bool as_dataset) {
  const std::string where = as_dataset ? g.dataset(name) : g.attribute(name);
  if (!as_dataset && !has_attr(g, name)) fail(g.file, where, "is missing");
  Handle obj = as_dataset ? Handle(H5Dopen2(g.id, name, H5P_DEFAULT), H5Dclose)
                          : Handle(H5Aopen(g.id, name, H5P_DEFAULT), H5Aclose);
  if (!obj.valid()) fail_h5(g.file, where, "is missing or cannot be opened");
  Handle stored(as_dataset ? H5Dget_type(obj.get()) : H5Aget_type(obj.get()), H5Tclose);
  Handle space(as_dataset ? H5Dget_space(obj.get()) : H5Aget_space(obj.get()), H5Sclose);
  if (H5Tis_variable_str(stored.get()) <= 0)
    fail(g.file, where, "does not hold variable-length strings");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail_h5(g.file, where, "has an unreadable shape");
  std::vector<char*> ptrs(static_cast<std::size_t>(n), nullptr);
  if (n > 0) {
    Handle mem = utf8_string_type();
    H5Tset_cset(mem.get(), H5Tget_cset(stored.get()));
    const herr_t st =
        as_dataset ? H5Dread(obj.get(), mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data())
                   : H5Aread(obj.get(), mem.get(), ptrs.data());
    if (st < 0) fail_h5(g.file, where, "cannot be read");
  }
  std::vector<std::string> out(ptrs.size());
  for (std::size_t i = 0; i < ptrs.size(); ++i) {
    if (ptrs[i]) out[i] = ptrs[i];
    H5free_memory(ptrs[i]);  // the library allocated them
  }
  return out;
}

// One named value of a metadata or clock table, stored as an attribute.
template <class T>
void write_field(const Loc& g, const char* name, const T& value) {
  if constexpr (std::is_same_v<T, std::string>) {
    write_strings(g, name, {value}, true, false);
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    write_strings(g, name, value, false, false);
  } else {
    write_attr<T>(g, name, value);
  }
}

template <class T>
void read_field(const Loc& g, const char* name, T& value) {
  if constexpr (std::is_same_v<T, std::string>) {
    auto v = read_strings(g, name, false);
    if (v.size() != 1) fail(g.file, g.attribute(name), "is not a single string");
    value = std::move(v[0]);
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    value = read_strings(g, name, false);
  } else {
    value = read_attr<T>(g, name);
  }
}

// How a per-particle array is stored: Vec<D> as D doubles per row (cols = D), scalars and
// Role as one value per row (cols = 0: a 1-D dataset).
template <class T>
struct Column {
  using Scalar = T;
  static constexpr int cols = 0;
};
template <>
struct Column<Role> {
  using Scalar = std::uint8_t;
  static constexpr int cols = 0;
};
template <class S, int R, int O, int MR, int MC>
struct Column<Eigen::Matrix<S, R, 1, O, MR, MC>> {
  using Scalar = S;
  static constexpr int cols = R;
};

// Creates dataset `name` of `rows` rows for a T per row, compressed (lossless: shuffle +
// deflate level 1) when asked and large. `early`: its storage is allocated now (a file that
// several ranks fill at once, parallel HDF5).
template <class T>
Handle create_column(const Loc& g, const char* name, std::size_t rows, bool compress,
                     bool early = false) {
  using S = typename Column<T>::Scalar;
  constexpr int cols = Column<T>::cols;
  const hsize_t width = cols > 0 ? cols : 1;
  static_assert(sizeof(T) == sizeof(S) * (cols > 0 ? cols : 1), "rows must be packed scalars");
  const hsize_t dims[2] = {rows, width};
  const int rank = cols > 0 ? 2 : 1;
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (compress && rows * width > kCompressAbove && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    const hsize_t chunk[2] = {std::min<hsize_t>(rows, std::max<hsize_t>(1, kChunkValues / width)),
                              width};
    H5Pset_chunk(dcpl.get(), rank, chunk);
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), 1);
  }
  if (early) H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY);
  Handle ds(
      H5Dcreate2(g.id, name, H5Types<S>::file(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      H5Dclose);
  if (!ds.valid()) fail_h5(g.file, g.dataset(name), "cannot be created");
  return ds;
}

// Writes the first `rows` entries of `v` as a new dataset (see create_column).
template <class T>
void write_column(const Loc& g, const char* name, const std::vector<T>& v, std::size_t rows,
                  bool compress) {
  using S = typename Column<T>::Scalar;
  Handle ds = create_column<T>(g, name, rows, compress);
  // An empty dataset is complete as created; HDF5 rejects a write from a null buffer.
  if (rows > 0 && H5Dwrite(ds.get(), H5Types<S>::mem(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                           reinterpret_cast<const S*>(v.data())) < 0)
    fail_h5(g.file, g.dataset(name), "cannot be written");
}

// Writes v[from, from + rows) into rows [first, first + rows) of the existing dataset `name`
// through the transfer list `dxpl`, collective in a file several ranks write: every rank calls
// this for the same datasets in the same order (rows = 0 included). `all_ok(bool)` combines a
// flag over those ranks (logical AND): the dataset is opened and the rows selected on every
// rank before any rank writes, so a failure there stops every rank at the same call.
template <class T, class AllOk>
void write_rows(const Loc& g, const char* name, const std::vector<T>& v, std::size_t from,
                std::size_t rows, std::uint64_t first, hid_t dxpl, AllOk&& all_ok) {
  using S = typename Column<T>::Scalar;
  constexpr int cols = Column<T>::cols;
  const hsize_t width = cols > 0 ? cols : 1;
  const int rank = cols > 0 ? 2 : 1;
  const hsize_t start[2] = {first, 0}, count[2] = {rows, width};
  Handle ds(H5Dopen2(g.id, name, H5P_DEFAULT), H5Dclose);
  Handle fspace(ds.valid() ? H5Dget_space(ds.get()) : -1, H5Sclose);
  Handle mspace(H5Screate_simple(rank, count, nullptr), H5Sclose);
  bool ok = ds.valid() && fspace.valid() && mspace.valid();
  if (ok && rows == 0) {
    ok = H5Sselect_none(fspace.get()) >= 0 && H5Sselect_none(mspace.get()) >= 0;
  } else if (ok) {
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(fspace.get(), dims, nullptr);
    ok = first + rows <= dims[0] &&
         H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) >= 0;
  }
  if (!all_ok(ok)) {
    if (!ok)
      fail_h5(g.file, g.dataset(name),
              "rows " + std::to_string(first) + "+" + std::to_string(rows) +
                  " cannot be opened or selected");
    fail(g.file, g.dataset(name), "another rank could not open or select its rows");
  }
  static const S none{};  // a rank with no rows still takes part, from a valid address
  const S* data = rows > 0 ? reinterpret_cast<const S*>(v.data() + from) : &none;
  if (H5Dwrite(ds.get(), H5Types<S>::mem(), mspace.get(), fspace.get(), dxpl, data) < 0)
    fail_h5(g.file, g.dataset(name), "cannot be written");
}

constexpr std::size_t kAnyRows = static_cast<std::size_t>(-1);

// Reads a whole dataset into `v` after checking its shape: `rows` rows (any number with
// kAnyRows) of the width that T needs. Returns the number of rows.
template <class T>
std::size_t read_column(const Loc& g, const char* name, std::size_t rows, std::vector<T>& v) {
  using S = typename Column<T>::Scalar;
  constexpr int cols = Column<T>::cols;
  Handle ds(H5Dopen2(g.id, name, H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail_h5(g.file, g.dataset(name), "is missing or cannot be opened");
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != (cols > 0 ? 2 : 1))
    fail(g.file, g.dataset(name),
         "has " + std::to_string(rank) + " dimensions, expected " +
             std::to_string(cols > 0 ? 2 : 1));
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  if ((rows != kAnyRows && dims[0] != rows) || (cols > 0 && dims[1] != hsize_t(cols))) {
    auto shape = [&](std::string r, hsize_t c) {
      return cols > 0 ? r + " x " + std::to_string(c) : r;
    };
    fail(g.file, g.dataset(name),
         "has shape " + shape(std::to_string(dims[0]), dims[1]) + ", expected " +
             shape(std::to_string(rows), cols));
  }
  v.resize(dims[0]);
  if (dims[0] > 0 && H5Dread(ds.get(), H5Types<S>::mem(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                             reinterpret_cast<S*>(v.data())) < 0)
    fail_h5(g.file, g.dataset(name), "cannot be read");
  return dims[0];
}

// Reads rows [first, first + count) of dataset `name` (which must have `rows` rows of the
// width T needs) into v[at, at + count) (v resized to hold them).
template <class T>
void read_rows(const Loc& g, const char* name, std::size_t rows, std::uint64_t first,
               std::size_t count, std::vector<T>& v, std::size_t at) {
  using S = typename Column<T>::Scalar;
  constexpr int cols = Column<T>::cols;
  const hsize_t width = cols > 0 ? cols : 1;
  const int rank = cols > 0 ? 2 : 1;
  Handle ds(H5Dopen2(g.id, name, H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail_h5(g.file, g.dataset(name), "is missing or cannot be opened");
  Handle fspace(H5Dget_space(ds.get()), H5Sclose);
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(fspace.get()) != rank)
    fail(g.file, g.dataset(name), "has the wrong number of dimensions");
  H5Sget_simple_extent_dims(fspace.get(), dims, nullptr);
  if (dims[0] != rows || (cols > 0 && dims[1] != width) || first + count > rows)
    fail(g.file, g.dataset(name),
         "has " + std::to_string(dims[0]) + " rows; expected " + std::to_string(rows) +
             " to read rows " + std::to_string(first) + "+" + std::to_string(count));
  if (v.size() < at + count) v.resize(at + count);
  if (count == 0) return;
  const hsize_t start[2] = {first, 0}, n[2] = {count, width};
  Handle mspace(H5Screate_simple(rank, n, nullptr), H5Sclose);
  if (H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, n, nullptr) < 0 ||
      H5Dread(ds.get(), H5Types<S>::mem(), mspace.get(), fspace.get(), H5P_DEFAULT,
              reinterpret_cast<S*>(v.data() + at)) < 0)
    fail_h5(g.file, g.dataset(name), "cannot be read");
}

// Names of the links in a group, in name order (snapshot names sort by step).
std::vector<std::string> child_names(const Loc& g) {
  H5G_info_t info;
  if (H5Gget_info(g.id, &info) < 0) fail_h5(g.file, "group '" + g.path + "'", "cannot be listed");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(g.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) fail_h5(g.file, "group '" + g.path + "'", "cannot be listed");
    std::vector<char> buf(static_cast<std::size_t>(len) + 1);
    H5Lget_name_by_idx(g.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf.data(), buf.size(),
                       H5P_DEFAULT);
    names.emplace_back(buf.data(), static_cast<std::size_t>(len));
  }
  return names;
}

}  // namespace swell::hdf5
