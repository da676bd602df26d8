#include "gphr/io/Hdf5File.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <filesystem>
#include <utility>
#ifdef __linux__
#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>
#endif

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

MPI_Comm rawComm(const RCP<const Comm>& comm) {
  auto mpi = Teuchos::rcp_dynamic_cast<const Teuchos::MpiComm<int>>(comm);
  return mpi.is_null() ? MPI_COMM_SELF : (*mpi->getRawMpiComm())();
}

// RAII for HDF5 identifiers.
struct Id {
  hid_t id;
  herr_t (*closer)(hid_t);
  ~Id() {
    if (id >= 0) closer(id);
  }
};

// What HDF5 said about the failure it just recorded (its printing is off, the stack is kept):
// the description of the innermost error, where it was detected, e.g. "incorrect metadata
// checksum after all read attempts" for a damaged header of a file in the 1.8 format.
// A failure anywhere in the data-filter pipeline or the plugin loader (by the error's class or its
// words) is said as such: its innermost error is the loader's ("can't open directory
// .../plugins"), which names no cause.
struct Hdf5Failure {
  std::string reason;
  bool filter = false;
};
herr_t innermostError(unsigned n, const H5E_error2_t* e, void* out) {
  auto& f = *static_cast<Hdf5Failure*>(out);
  if (n == 0 && e->desc != nullptr) f.reason = e->desc;
  const std::string desc = e->desc ? e->desc : "";
  if (e->maj_num == H5E_PLINE || e->maj_num == H5E_PLUGIN || desc.find("filter") != std::string::npos ||
      desc.find("plugin") != std::string::npos)
    f.filter = true;
  return 0;
}

std::string hdf5Reason() {
  Hdf5Failure f;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermostError, &f);
  if (f.filter)
    return " (HDF5: the dataset is stored through a filter -- compression or another plugin -- that this HDF5 cannot "
           "apply; allowed: datasets without filters, as gphr writes them)";
  return f.reason.empty() ? std::string() : " (HDF5: " + f.reason + ")";
}

// writing: the call wrote (a full disk is then a likely cause).
void check(herr_t status, const std::string& what, const std::string& path, bool writing = false) {
  if (status >= 0) return;
  // HDF5 says "file write failed" for a full disk: say so where the system's reason (errno, which
  // HDF5's cleanup may overwrite) or, for a write, the file system (no block left) shows it.
  const int why = errno;
  std::string system = why == ENOSPC || why == EDQUOT ? std::string(": ") + std::strerror(why) : "";
#ifdef __linux__
  const std::string dir = std::filesystem::path(path).parent_path().string();
  struct statvfs fs {};
  if (writing && system.empty() && ::statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0 && fs.f_bavail == 0)
    system = std::string(": ") + std::strerror(ENOSPC);
#endif
  throw InputError(detail::concat("HDF5 file '", path, "': ", what, " failed", hdf5Reason(), system));
}

// check() of a collective write, whose failure MPI-IO may report on some ranks only (the
// aggregators that wrote): every rank throws when any failed, so none goes on to the next
// collective call without the others (a hang, or a crash inside HDF5).
void checkOnAll(herr_t status, const RCP<const Comm>& comm, const std::string& what, const std::string& path) {
  const int why = errno, mine = status < 0 ? -1 : 0;
  int worst = mine;
  if (comm->getSize() > 1) Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, mine, Teuchos::outArg(worst));
  errno = why;
  check(status < 0 || worst == 0 ? status : herr_t(-1), what + (status >= 0 && worst < 0 ? " (on another rank)" : ""),
        path, true);
}

hid_t collectiveTransfer() {
  hid_t p = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(p, H5FD_MPIO_COLLECTIVE);
  return p;
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, const RCP<const Comm>& comm, Mode mode) : path_(path), comm_(comm) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions with the file name
  Id fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  H5Pset_fapl_mpio(fapl.id, rawComm(comm), MPI_INFO_NULL);
  // The 1.8 file format: its superblock and object headers (the attributes, links and dataset
  // layouts) carry checksums, which HDF5 verifies on every read, so a damaged header is a read
  // error instead of garbage the library follows (the earliest format, HDF5's default, has none:
  // one flipped bit in a model file's root attributes could crash libhdf5), and it stores an
  // attribute over 64 KiB (a fingerprint of 8,192+ snapshots) that the earliest refuses. Readable
  // by any HDF5 since 1.8 (2008); not the 1.10 format, whose new chunk indexes this project does
  // not need. Also for a file opened to write: what is added to an older file is in this format.
  if (mode != Mode::ReadOnly)
    check(H5Pset_libver_bounds(fapl.id, H5F_LIBVER_V18, H5F_LIBVER_V18), "choosing the 1.8 file format", path);
  if (mode == Mode::Create) {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id);
    GPHR_REQUIRE(file_ >= 0, InputError, "cannot create HDF5 file '", path, "' (is the directory writable?)");
  } else {
    // Checked before HDF5's MPI-IO driver opens it: on a directory it prints one error per read.
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    GPHR_REQUIRE(st.type() != std::filesystem::file_type::not_found, InputError, "cannot open HDF5 file '", path,
                 "': no such file");
    GPHR_REQUIRE(st.type() == std::filesystem::file_type::regular, InputError, "cannot open HDF5 file '", path,
                 "': it is ", st.type() == std::filesystem::file_type::directory ? "a directory" : "not a regular file",
                 "; allowed: an HDF5 file");
    file_ = H5Fopen(path.c_str(), mode == Mode::ReadOnly ? H5F_ACC_RDONLY : H5F_ACC_RDWR, fapl.id);
    GPHR_REQUIRE(file_ >= 0, InputError, "cannot open HDF5 file '", path,
                 "': missing, truncated or not an HDF5 file");
  }
}

Hdf5File::~Hdf5File() { close(); }

namespace {
std::atomic<bool> aCloseFailed{false};  // Hdf5File::closeFailed()
}  // namespace

void Hdf5File::close() {
  if (file_ >= 0 && writeFailed_ && comm_->getSize() > 1) aCloseFailed = true;  // see the declaration
  else if (file_ >= 0 && H5Fclose(file_) < 0) aCloseFailed = true;
  file_ = -1;
}

void Hdf5File::checkWrite(herr_t status, const std::string& what) {
  try {
    checkOnAll(status, comm_, what, path_);
  } catch (...) {
    writeFailed_ = true;
    throw;
  }
}

bool Hdf5File::closeFailed() { return aCloseFailed; }

bool Hdf5File::exists(const std::string& name) const {
  if (name == "/") return true;
  // Check each path component so that a missing parent is "false", not an error.
  size_t pos = 0;
  while ((pos = name.find('/', pos + 1)) != std::string::npos)
    if (!linkExists(name.substr(0, pos))) return false;
  return linkExists(name);
}

bool Hdf5File::linkExists(const std::string& name) const {
  const htri_t found = H5Lexists(file_, name.c_str(), H5P_DEFAULT);
  // An error (not "absent") is a damaged file: reading the group's links failed.
  check(found, "looking up '" + name + "'", path_);
  return found > 0;
}

void Hdf5File::createGroup(const std::string& name) {
  Id g{H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
  check(g.id, "creating group '" + name + "'", path_);
}

void Hdf5File::remove(const std::string& name) {
  if (exists(name)) check(H5Ldelete(file_, name.c_str(), H5P_DEFAULT), "removing '" + name + "'", path_);
}

bool Hdf5File::hasAttribute(const std::string& object, const std::string& key) const {
  if (!exists(object)) return false;
  const htri_t found = H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT);
  check(found, "looking up attribute '" + key + "' of '" + object + "'", path_);
  return found > 0;
}

void Hdf5File::flush() { checkWrite(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing"); }

void Hdf5File::startWriteback() const {
#ifdef __linux__
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE);  // 0, 0: the whole file
  ::close(fd);
#endif
}

hid_t Hdf5File::openDataset(const std::string& name) const {
  GPHR_REQUIRE(exists(name), InputError, "HDF5 file '", path_, "' has no dataset '", name, "'");
  hid_t d = H5Dopen2(file_, name.c_str(), H5P_DEFAULT);
  check(d, "opening dataset '" + name + "'", path_);
  return d;
}

namespace {
// Rows 0, every, 2 every, ... of `count`: how many.
hsize_t everyNth(hsize_t count, hsize_t every) { return (count + every - 1) / every; }

// File-space selection of this rank's entries of `rows` states, rows first, first + every, ...:
// columns [a, a+m) and [n+a, n+a+m). HDF5 orders the selected elements row-major, which is the
// local layout (q block then p block) of each state.
void selectLocal(hid_t space, hsize_t first, hsize_t every, hsize_t rows, const PhaseSpace& ps) {
  const hsize_t m = ps.numLocalDofs(), a = ps.firstLocalDof(), n = ps.n();
  if (m == 0 || rows == 0) {
    H5Sselect_none(space);
    return;
  }
  hsize_t start[2] = {first, a}, stride[2] = {every, 1}, cnt[2] = {rows, m};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, stride, cnt, nullptr);
  start[1] = n + a;
  H5Sselect_hyperslab(space, H5S_SELECT_OR, start, stride, cnt, nullptr);
}

// A MultiVector's host view, read-only (kept alive while HDF5 reads from it).
using HostView = decltype(std::declval<const MultiVector&>().getLocalViewHost(Tpetra::Access::ReadOnly));

// X's columns, each rank's entries, row after row (the memory order of a row-major selection).
std::vector<double> rowMajor(const MultiVector* X) {
  const hsize_t local = X ? X->getLocalLength() : 0, count = X ? X->getNumVectors() : 0;
  std::vector<double> buf(std::max<hsize_t>(count * local, 1));
  if (X) {
    auto v = X->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (hsize_t j = 0; j < count; ++j)
      for (hsize_t i = 0; i < local; ++i) buf[j * local + i] = v(i, j);
  }
  return buf;
}
}  // namespace

// Columns of X as rows of a (cols, N) dataset; `select` picks this rank's entries of each row in
// the order of its local rows.
void Hdf5File::writeDistributed(const std::string& name, hsize_t count, hsize_t N, const MultiVector* X,
                                const Selector& select) {
  GPHR_REQUIRE(!X || X->getNumVectors() == count, InputError, "writing dataset '", name, "': ", X ? X->getNumVectors() : 0,
               " columns for ", count, " rows");
  createStates(name, count, N);
  writeRows(name, 0, count, X, select);
}

void Hdf5File::createStates(const std::string& name, hsize_t count, hsize_t fullDim) {
  hsize_t dims[2] = {count, fullDim};
  Id fspace{H5Screate_simple(2, dims, nullptr), H5Sclose};
  Id dset{H5Dcreate2(file_, name.c_str(), H5T_NATIVE_DOUBLE, fspace.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Dclose};
  check(dset.id, "creating dataset '" + name + "'", path_);
}

void Hdf5File::writeRows(const std::string& name, hsize_t first, hsize_t rows, const MultiVector* X,
                         const Selector& select, hsize_t width) {
  GPHR_REQUIRE(!X || X->getNumVectors() == rows, InputError, "writing dataset '", name, "': ",
               X ? X->getNumVectors() : 0, " columns for ", rows, " rows");
  Id dset{openDataset(name), H5Dclose};
  Id fspace{H5Dget_space(dset.id), H5Sclose};
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(fspace.id, dims, nullptr);
  GPHR_REQUIRE(first + rows <= dims[0], InputError, "writing rows ", first, " to ", first + rows, " of dataset '", name,
               "' of ", dims[0], " rows (allowed: within them)");
  GPHR_REQUIRE(width == 0 || width == dims[1], InputError, "writing states of ", width, " entries into dataset '", name,
               "' of states of ", dims[1]);
  const hsize_t local = X ? X->getLocalLength() : 0;
  // Columns that lie back to back (constant stride = the local rows) are already in the
  // selection's order, row after row: HDF5 takes them where they are; others go through a copy.
  std::vector<double> copy;
  HostView view;
  const double* data = nullptr;
  if (X && rows * local > 0 && X->isConstantStride() && (rows == 1 || X->getStride() == local)) {
    view = X->getLocalViewHost(Tpetra::Access::ReadOnly);
    data = view.data();
  } else {
    copy = rowMajor(X);
    data = copy.data();
  }
  if (X)
    select(fspace.id, first, 1, rows);
  else
    H5Sselect_none(fspace.id);
  hsize_t mdims[1] = {std::max<hsize_t>(rows * local, 1)};
  Id mspace{H5Screate_simple(1, mdims, nullptr), H5Sclose};
  if (rows * local == 0) H5Sselect_none(mspace.id);
  Id xfer{collectiveTransfer(), H5Pclose};
  checkWrite(H5Dwrite(dset.id, H5T_NATIVE_DOUBLE, mspace.id, fspace.id, xfer.id, data), "writing dataset '" + name + "'");
}

RCP<MultiVector> Hdf5File::readDistributed(const std::string& name, const RCP<const Map>& map, hsize_t N,
                                           const Selector& select, const char* what, hsize_t every, hsize_t first,
                                           hsize_t columns) const {
  Id dset{openDataset(name), H5Dclose};
  Id fspace{H5Dget_space(dset.id), H5Sclose};
  hsize_t dims[2] = {0, 0};
  GPHR_REQUIRE(H5Sget_simple_extent_ndims(fspace.id) == 2, InputError, "HDF5 file '", path_,
               "': dataset '", name, "' is not a 2-D array of ", what, "s");
  H5Sget_simple_extent_dims(fspace.id, dims, nullptr);
  GPHR_REQUIRE(dims[1] == N, InputError, "HDF5 file '", path_, "': dataset '", name, "' holds ", what,
               "s of size ", dims[1], " but the model has size ", N);
  GPHR_REQUIRE(every >= 1, InputError, "reading dataset '", name, "': every ", every, " th row; allowed: >= 1");
  const hsize_t used = everyNth(dims[0], every);
  GPHR_REQUIRE(first <= used && (columns == kAllRows || columns <= used - first), InputError, "reading dataset '",
               name, "': ", columns == kAllRows ? std::string("all") : std::to_string(columns), " of its every-",
               every, " rows from the ", first, "-th; allowed: within its ", used, " such rows");
  const hsize_t count = columns == kAllRows ? used - first : columns, local = map->getNodeNumElements();
  select(fspace.id, first * every, every, count);
  hsize_t mdims[1] = {std::max<hsize_t>(count * local, 1)};
  Id mspace{H5Screate_simple(1, mdims, nullptr), H5Sclose};
  if (count * local == 0) H5Sselect_none(mspace.id);
  Id xfer{collectiveTransfer(), H5Pclose};
  auto out = rcp(new MultiVector(map, std::max<hsize_t>(count, 1)));
  auto v = out->getLocalViewHost(Tpetra::Access::OverwriteAll);
  // The selection's order (row after row) is the columns' when they lie back to back: read into
  // the MultiVector itself; otherwise through a copy.
  const bool inPlace = count * local > 0 && out->isConstantStride() && (count == 1 || out->getStride() == local);
  std::vector<double> buf(inPlace ? 1 : std::max<hsize_t>(count * local, 1));
  check(H5Dread(dset.id, H5T_NATIVE_DOUBLE, mspace.id, fspace.id, xfer.id, inPlace ? v.data() : buf.data()),
        "reading dataset '" + name + "' (truncated file?)", path_);
  if (!inPlace)
    for (hsize_t j = 0; j < count; ++j)
      for (hsize_t i = 0; i < local; ++i) v(i, j) = buf[j * local + i];
  return out;
}

void Hdf5File::writeStates(const std::string& name, const MultiVector& states, const PhaseSpace& ps) {
  writeDistributed(name, states.getNumVectors(), ps.fullDim(), &states,
                   [&](hid_t sp, hsize_t first, hsize_t every, hsize_t rows) { selectLocal(sp, first, every, rows, ps); });
}

void Hdf5File::writeStateRows(const std::string& name, hsize_t first, hsize_t b, const MultiVector* states,
                              const PhaseSpace* groupSpace) {
  GPHR_REQUIRE(!states == !groupSpace, InputError, "writing states '", name,
               "' from a rank group: states and phase space (need both or neither)");
  writeRows(
      name, first, b, states,
      [&](hid_t sp, hsize_t f, hsize_t every, hsize_t rows) { selectLocal(sp, f, every, rows, *groupSpace); },
      groupSpace ? static_cast<hsize_t>(groupSpace->fullDim()) : 0);
}

RCP<MultiVector> Hdf5File::readStates(const std::string& name, const PhaseSpace& ps) const {
  return readStates(name, ps, 1);
}

RCP<MultiVector> Hdf5File::readStates(const std::string& name, const PhaseSpace& ps, hsize_t every) const {
  return readStates(name, ps, every, 0, kAllRows);
}

RCP<MultiVector> Hdf5File::readStates(const std::string& name, const PhaseSpace& ps, hsize_t every, hsize_t first,
                                      hsize_t columns) const {
  return readDistributed(
      name, ps.map(), ps.fullDim(),
      [&](hid_t sp, hsize_t f, hsize_t ev, hsize_t rows) { selectLocal(sp, f, ev, rows, ps); }, "state", every, first,
      columns);
}

namespace {
void selectContiguous(hid_t space, hsize_t first, hsize_t every, hsize_t rows, const Map& map) {
  const hsize_t m = map.getNodeNumElements();
  if (m == 0 || rows == 0) {
    H5Sselect_none(space);
    return;
  }
  hsize_t start[2] = {first, static_cast<hsize_t>(map.getMinGlobalIndex() - map.getMinAllGlobalIndex())};
  hsize_t stride[2] = {every, 1}, cnt[2] = {rows, m};
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start, stride, cnt, nullptr);
}
}  // namespace

void Hdf5File::writeColumns(const std::string& name, const MultiVector& X) {
  const Map& map = *X.getMap();
  GPHR_REQUIRE(map.isContiguous(), InputError, "writeColumns '", name, "': the map must be contiguous");
  writeDistributed(name, X.getNumVectors(), map.getGlobalNumElements(), &X,
                   [&](hid_t sp, hsize_t first, hsize_t every, hsize_t rows) {
                     selectContiguous(sp, first, every, rows, map);
                   });
}

RCP<MultiVector> Hdf5File::readColumns(const std::string& name, const RCP<const Map>& map) const {
  GPHR_REQUIRE(map->isContiguous(), InputError, "readColumns '", name, "': the map must be contiguous");
  return readDistributed(name, map, map->getGlobalNumElements(),
                         [&](hid_t sp, hsize_t first, hsize_t every, hsize_t rows) {
                           selectContiguous(sp, first, every, rows, *map);
                         },
                         "row");
}

void Hdf5File::writeArray(const std::string& name, const std::vector<double>& data, size_t rows, size_t cols) {
  GPHR_REQUIRE(data.size() == rows * cols, InputError, "writeArray '", name, "': ", data.size(),
               " values for a ", rows, " x ", cols, " array");
  hsize_t dims[2] = {rows, cols};
  Id fspace{H5Screate_simple(2, dims, nullptr), H5Sclose};
  Id dset{H5Dcreate2(file_, name.c_str(), H5T_NATIVE_DOUBLE, fspace.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Dclose};
  check(dset.id, "creating dataset '" + name + "'", path_);
  const bool root = comm_->getRank() == 0;
  hsize_t mdims[1] = {std::max<size_t>(data.size(), 1)};
  Id mspace{H5Screate_simple(1, mdims, nullptr), H5Sclose};
  if (!root || data.empty()) {
    H5Sselect_none(fspace.id);
    H5Sselect_none(mspace.id);
  }
  Id xfer{collectiveTransfer(), H5Pclose};
  const double dummy = 0.0;
  checkWrite(H5Dwrite(dset.id, H5T_NATIVE_DOUBLE, mspace.id, fspace.id, xfer.id, data.empty() ? &dummy : data.data()),
             "writing dataset '" + name + "'");
}

std::vector<double> Hdf5File::readArray(const std::string& name, size_t* rows, size_t* cols) const {
  Id dset{openDataset(name), H5Dclose};
  Id fspace{H5Dget_space(dset.id), H5Sclose};
  hsize_t dims[2] = {1, 1};
  const int nd = H5Sget_simple_extent_ndims(fspace.id);
  GPHR_REQUIRE(nd >= 1 && nd <= 2, InputError, "HDF5 file '", path_, "': dataset '", name, "' is not 1-D or 2-D");
  H5Sget_simple_extent_dims(fspace.id, dims, nullptr);
  if (nd == 1) dims[1] = 1;
  Id type{H5Dget_type(dset.id), H5Tclose};
  const H5T_class_t cls = H5Tget_class(type.id);
  GPHR_REQUIRE(cls == H5T_FLOAT || cls == H5T_INTEGER, InputError, "HDF5 file '", path_, "': dataset '", name,
               "' is not numeric; allowed: numbers");
  // Checked before allocating: a dataset resized beyond the file's bytes (its chunks unwritten)
  // would claim memory the file never held. GPHR writes contiguous, uncompressed data.
  hsize_t fileBytes = 0;
  H5Fget_filesize(file_, &fileBytes);
  const double elements = double(dims[0]) * double(dims[1]);
  GPHR_REQUIRE(elements * sizeof(double) <= double(fileBytes) + 1048576.0, InputError, "HDF5 file '", path_,
               "': dataset '", name, "' claims ", dims[0], " x ", dims[1], " values in a file of ", fileBytes,
               " bytes; allowed: values the file holds");
  std::vector<double> out(dims[0] * dims[1]);
  Id xfer{collectiveTransfer(), H5Pclose};
  check(H5Dread(dset.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, xfer.id, out.data()),
        "reading dataset '" + name + "' (truncated file?)", path_);
  if (rows) *rows = dims[0];
  if (cols) *cols = dims[1];
  return out;
}

void Hdf5File::setAttribute(const std::string& object, const std::string& key, const std::string& value) {
  Id type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, std::max<size_t>(value.size(), 1));
  Id space{H5Screate(H5S_SCALAR), H5Sclose};
  if (H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT);
  Id attr{H5Acreate_by_name(file_, object.c_str(), key.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
          H5Aclose};
  check(attr.id, "creating attribute '" + key + "' on '" + object + "'", path_);
  std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attr.id, type.id, padded.data()), "writing attribute '" + key + "'", path_);
}

void Hdf5File::setAttribute(const std::string& object, const std::string& key, const std::vector<double>& value) {
  hsize_t dims[1] = {std::max<size_t>(value.size(), 1)};
  Id space{H5Screate_simple(1, dims, nullptr), H5Sclose};
  if (H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT);
  Id attr{H5Acreate_by_name(file_, object.c_str(), key.c_str(), H5T_NATIVE_DOUBLE, space.id, H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose};
  check(attr.id, "creating attribute '" + key + "' on '" + object + "'", path_);
  std::vector<double> v = value.empty() ? std::vector<double>{0.0} : value;
  check(H5Awrite(attr.id, H5T_NATIVE_DOUBLE, v.data()), "writing attribute '" + key + "'", path_);
}

std::string Hdf5File::stringAttribute(const std::string& object, const std::string& key) const {
  GPHR_REQUIRE(H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) > 0, InputError,
               "HDF5 file '", path_, "': '", object, "' has no attribute '", key, "'");
  Id attr{H5Aopen_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  Id type{H5Aget_type(attr.id), H5Tclose};
  Id space{H5Aget_space(attr.id), H5Sclose};
  GPHR_REQUIRE(H5Tget_class(type.id) == H5T_STRING && H5Sget_simple_extent_npoints(space.id) == 1, InputError,
               "HDF5 file '", path_, "': attribute '", key, "' of '", object,
               "' is not a string; allowed: one fixed- or variable-length string");
  if (H5Tis_variable_str(type.id) > 0) {  // as h5py and other writers make them
    Id memType{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(memType.id, H5T_VARIABLE);
    H5Tset_cset(memType.id, H5Tget_cset(type.id));  // ASCII or UTF-8, as the writer chose
    char* value = nullptr;
    check(H5Aread(attr.id, memType.id, &value), "reading attribute '" + key + "'", path_);
    std::string out = value ? value : "";
    H5free_memory(value);
    return out;
  }
  std::string s(H5Tget_size(type.id), '\0');
  check(H5Aread(attr.id, type.id, s.data()), "reading attribute '" + key + "'", path_);
  return s.substr(0, s.find('\0'));
}

std::vector<double> Hdf5File::doubleAttribute(const std::string& object, const std::string& key) const {
  GPHR_REQUIRE(H5Aexists_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT) > 0, InputError,
               "HDF5 file '", path_, "': '", object, "' has no attribute '", key, "'");
  Id attr{H5Aopen_by_name(file_, object.c_str(), key.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  Id type{H5Aget_type(attr.id), H5Tclose};
  const H5T_class_t cls = H5Tget_class(type.id);
  GPHR_REQUIRE(cls == H5T_FLOAT || cls == H5T_INTEGER, InputError, "HDF5 file '", path_, "': attribute '", key,
               "' of '", object, "' is not numeric; allowed: numbers");
  Id space{H5Aget_space(attr.id), H5Sclose};
  std::vector<double> v(H5Sget_simple_extent_npoints(space.id));
  check(H5Aread(attr.id, H5T_NATIVE_DOUBLE, v.data()), "reading attribute '" + key + "'", path_);
  return v;
}

RenameOnCommit::RenameOnCommit(std::string finalPath, RCP<const Comm> comm)
    : final_(std::move(finalPath)), temp_(final_ + ".partial"), comm_(comm) {}

RenameOnCommit::~RenameOnCommit() {
  if (!done_ && comm_->getRank() == 0) std::remove(temp_.c_str());
}

void RenameOnCommit::commit() {
  comm_->barrier();
  // Rank 0 renames; its failure is every rank's (a rank that threw alone would leave the others
  // waiting in their next collective).
  int error = 0;
  if (comm_->getRank() == 0 && std::rename(temp_.c_str(), final_.c_str()) != 0) error = errno ? errno : EIO;
  Teuchos::broadcast(*comm_, 0, Teuchos::outArg(error));
  GPHR_REQUIRE(error == 0, InputError, "cannot rename '", temp_, "' to '", final_, "': ", std::strerror(error));
  done_ = true;
}

}  // namespace gphr
