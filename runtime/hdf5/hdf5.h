#pragma once
/// @file hdf5.h
/// Checked RAII wrappers around the HDF5 C API (namespace wrc::h5).
///
/// Every HDF5 call made through these classes is checked; a failure throws wrc::h5::Error naming
/// the file, the object path inside it and what failed, with HDF5's own innermost error message
/// appended. HDF5's automatic error printing to stderr is switched off. This header deliberately
/// does not include <hdf5.h>, so users of the wrapper cannot call the raw API by accident; the
/// project rule is that raw H5* calls live in runtime/hdf5/ only.
///
/// Reading covers what the runtime needs (string and string-array attributes, integer and float
/// attributes, N-D numeric datasets); writing covers what a table writer needs (files, groups,
/// chunked datasets with deflate and fletcher32, attributes, hyperslab blocks).
///
/// Thread safety: objects are not shared between threads. Debian's libhdf5 is built thread-safe,
/// but other builds are not; code that uses HDF5 from several threads holds h5::LibraryLock().

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace wrc::h5 {

/// hid_t of the HDF5 C API (a 64-bit integer since HDF5 1.10; checked in hdf5.cpp).
using Id = std::int64_t;
/// hsize_t of the HDF5 C API (checked in hdf5.cpp).
using Size = unsigned long long;

/// Any failure of an HDF5 operation. what() reads "<file>:<object path>: <problem>".
class Error : public std::runtime_error {
 public:
  /// @param object Where it happened, "<file>:<path>" (see Object::Where()).
  /// @param problem What failed, including HDF5's own message when there is one.
  Error(const std::string& object, const std::string& problem);
  /// The file and object path the error refers to.
  const std::string& Location() const noexcept { return object_; }

 private:
  std::string object_;
};

/// Tells HDF5 not to close files from its exit handler; call it before any other HDF5 use. A file
/// whose close failed (a full disk) stays registered in HDF5 1.10, and closing it again at exit
/// crashes (SIGSEGV in H5F__close_cb). Programs that close every file themselves call this.
void SkipLibraryTermination();

/// Serialises HDF5 use across threads (recursive: nested wrapper calls may lock again).
std::unique_lock<std::recursive_mutex> LibraryLock();

/// Largest dataset or attribute a whole read accepts, in bytes of memory (16 GiB: ten times the
/// largest table the generator is meant for; anything larger is a damaged dataspace).
constexpr std::size_t kMaxReadBytes = std::size_t{1} << 34;

/// Element types the wrapper reads and writes; memory is in native byte order, HDF5 converts.
enum class ElementType { kFloat64, kFloat32, kInt8, kUInt8, kInt32, kInt64 };

/// Maps a C++ element type to ElementType (specialised below for the supported types).
template <typename T>
struct ElementTypeOf;
template <>
struct ElementTypeOf<double> {
  static constexpr ElementType value = ElementType::kFloat64;
};
template <>
struct ElementTypeOf<float> {
  static constexpr ElementType value = ElementType::kFloat32;
};
template <>
struct ElementTypeOf<std::int8_t> {
  static constexpr ElementType value = ElementType::kInt8;
};
template <>
struct ElementTypeOf<std::uint8_t> {
  static constexpr ElementType value = ElementType::kUInt8;
};
template <>
struct ElementTypeOf<std::int32_t> {
  static constexpr ElementType value = ElementType::kInt32;
};
template <>
struct ElementTypeOf<std::int64_t> {
  static constexpr ElementType value = ElementType::kInt64;
};

/// Class of a stored datatype, as far as readers need to tell them apart.
enum class TypeClass { kInteger, kFloat, kString, kOther };

/// How strings are stored: variable length (h5py's default for str) or fixed length,
/// null-padded to the longest (what NumPy byte strings give). Readers accept both.
enum class StringStorage { kVariable, kFixed };

/// Owns one HDF5 identifier and releases it with the matching H5*close call. Move-only.
class Handle {
 public:
  enum class Kind { kFile, kGroup, kDataset, kDataspace, kAttribute, kDatatype, kPropertyList };

  Handle() = default;
  Handle(Id id, Kind kind) : id_(id), kind_(kind) {}
  Handle(Handle&& other) noexcept : id_(other.id_), kind_(other.kind_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  /// Closes the identifier; a failing close cannot throw here and is ignored.
  ~Handle() { Reset(); }

  Id id() const noexcept { return id_; }
  bool valid() const noexcept { return id_ >= 0; }
  /// Closes the identifier now (no-op when empty).
  void Reset() noexcept;

 private:
  Id id_ = -1;
  Kind kind_ = Kind::kFile;
};

/// Shape of a dataset or attribute.
class Dataspace {
 public:
  /// A simple (N-D) dataspace with the given dimensions; rank 0 gives a scalar dataspace.
  static Dataspace Simple(const std::vector<Size>& dims);
  Dataspace(Handle handle, std::string where)
      : handle_(std::move(handle)), where_(std::move(where)) {}

  Id id() const noexcept { return handle_.id(); }
  bool IsScalar() const;
  int Rank() const;
  std::vector<Size> Dims() const;
  Size NumElements() const;

 private:
  Handle handle_;
  std::string where_;
};

/// A stored (file) datatype, for inspection.
class Datatype {
 public:
  Datatype(Handle handle, std::string where)
      : handle_(std::move(handle)), where_(std::move(where)) {}

  Id id() const noexcept { return handle_.id(); }
  TypeClass Class() const;
  /// Size of one element in bytes (for variable-length strings: the size of the pointer).
  std::size_t ElementSize() const;
  /// Human-readable description for error messages, e.g. "float64", "int8", "string".
  std::string Describe() const;
  /// Whether the stored type is exactly the standard type of `type` (IEEE float or two's
  /// complement integer of that size, either byte order): sizes, precision, offsets and the
  /// exponent and mantissa layout all match.
  bool Is(ElementType type) const;
  /// Whether the stored type is one of the standard numeric types of ElementType (either byte
  /// order). Reads refuse anything else before HDF5 converts a single byte: a damaged datatype
  /// message (a "float" of 65544 bytes) must be an error, not a conversion through it.
  bool IsStandardNumeric() const;

 private:
  Handle handle_;
  std::string where_;
};

/// An attribute attached to a group or dataset.
class Attribute {
 public:
  Attribute(Handle handle, std::string where)
      : handle_(std::move(handle)), where_(std::move(where)) {}

  /// "<file>:<object path>@<attribute name>", used in error messages.
  const std::string& Where() const noexcept { return where_; }
  Id id() const noexcept { return handle_.id(); }
  Datatype Type() const;
  Dataspace Space() const;
  /// A scalar string (fixed or variable length); throws if the attribute is not one string.
  std::string ReadString() const;
  /// A 1-D array of strings (fixed or variable length); a scalar string reads as one element.
  std::vector<std::string> ReadStrings() const;
  /// A scalar integer; throws if the stored class is not integer.
  std::int64_t ReadInt() const;
  /// A scalar number (integer or float class).
  double ReadDouble() const;

 private:
  Handle handle_;
  std::string where_;
};

/// Common part of groups, files and datasets: identity and attributes.
class Object {
 public:
  Id id() const noexcept { return handle_.id(); }
  /// Name of the file the object lives in, as given when opening it.
  const std::string& FileName() const noexcept { return file_; }
  /// Absolute path inside the file, e.g. "/axes/y".
  const std::string& Path() const noexcept { return path_; }
  /// "<file>:<path>", the prefix of error messages about this object.
  std::string Where() const { return file_ + ":" + path_; }

  bool HasAttribute(const std::string& name) const;
  Attribute OpenAttribute(const std::string& name) const;
  /// Names of all attributes, in name order.
  std::vector<std::string> AttributeNames() const;
  void RemoveAttribute(const std::string& name);

  std::string ReadStringAttribute(const std::string& name) const {
    return OpenAttribute(name).ReadString();
  }
  std::vector<std::string> ReadStringArrayAttribute(const std::string& name) const {
    return OpenAttribute(name).ReadStrings();
  }
  std::int64_t ReadIntAttribute(const std::string& name) const {
    return OpenAttribute(name).ReadInt();
  }
  double ReadDoubleAttribute(const std::string& name) const {
    return OpenAttribute(name).ReadDouble();
  }

  /// Writes (replacing an existing attribute of that name) a UTF-8 string. Fixed length (the
  /// default) keeps the text inside the object header, which the checksummed file format
  /// protects; variable-length strings live in HDF5's global heap, which carries no checksum
  /// (and a damaged one crashes HDF5 1.10 on read). In the checksummed format attributes of any
  /// size fit (dense storage); the earliest format limits an object's attributes to 64 KiB.
  void WriteStringAttribute(const std::string& name, std::string_view value,
                            StringStorage storage = StringStorage::kFixed);
  /// A 1-D array of UTF-8 strings.
  void WriteStringArrayAttribute(const std::string& name, const std::vector<std::string>& values,
                                 StringStorage storage = StringStorage::kFixed);
  /// A scalar native int64.
  void WriteIntAttribute(const std::string& name, std::int64_t value);
  /// A scalar native float64.
  void WriteDoubleAttribute(const std::string& name, double value);

 protected:
  Object(Handle handle, std::string file, std::string path)
      : handle_(std::move(handle)), file_(std::move(file)), path_(std::move(path)) {}
  /// Path of a child called name.
  std::string ChildPath(const std::string& name) const;

  Handle handle_;
  std::string file_;
  std::string path_;
};

/// Storage options of a new dataset.
struct DatasetOptions {
  /// Chunk dimensions; empty means contiguous storage, unless a filter below needs chunks, in
  /// which case a chunk shape of at most about 1 MiB is chosen from the dataset shape.
  std::vector<Size> chunk;
  /// Deflate (gzip) level 0–9; negative: no compression.
  int deflate_level = -1;
  /// Byte shuffle before deflate (helps floating-point data compress).
  bool shuffle = false;
  /// Fletcher-32 checksum per chunk; reading a corrupted chunk then fails instead of returning
  /// wrong numbers.
  bool fletcher32 = false;
};

/// Convenience: chunked, shuffled, deflate level 4, fletcher32, the generator's table default.
inline DatasetOptions CompressedChecked() {
  DatasetOptions options;
  options.deflate_level = 4;
  options.shuffle = true;
  options.fletcher32 = true;
  return options;
}

/// An N-D dataset of numbers.
class Dataset : public Object {
 public:
  Dataset(Handle handle, std::string file, std::string path)
      : Object(std::move(handle), std::move(file), std::move(path)) {}

  Dataspace Space() const;
  Datatype Type() const;
  /// Dimensions; empty for a scalar dataset.
  std::vector<Size> Shape() const { return Space().Dims(); }
  Size NumElements() const { return Space().NumElements(); }
  /// Chunk dimensions, empty when the dataset is not chunked.
  std::vector<Size> ChunkShape() const;
  bool HasDeflate() const;
  bool HasFletcher32() const;
  /// Throws unless every filter of the dataset is one the wrapper knows (shuffle, deflate,
  /// fletcher32) with parameters that fit the stored type: a damaged filter parameter (a
  /// shuffle element size that is not the type's) would otherwise decode to wrong numbers
  /// whose checksum, taken on the stored bytes, is fine. Reads call it.
  void CheckFilters() const;

  /// Reads the whole dataset (row-major), converting to T; throws when the stored class is not
  /// numeric or a value does not fit T.
  template <typename T>
  std::vector<T> Read() const {
    std::vector<T> values(CheckedCount(sizeof(T)));
    ReadRaw(ElementTypeOf<T>::value, values.data(), values.size());
    return values;
  }
  /// Writes the whole dataset from count values (count must equal NumElements()).
  template <typename T>
  void Write(const T* values, std::size_t count) {
    WriteRaw(ElementTypeOf<T>::value, values, count);
  }
  template <typename T>
  void Write(const std::vector<T>& values) {
    Write(values.data(), values.size());
  }
  /// Writes a block (hyperslab) starting at offset with extent count; values row-major.
  template <typename T>
  void WriteBlock(const std::vector<Size>& offset, const std::vector<Size>& count,
                  const T* values) {
    BlockRaw(true, ElementTypeOf<T>::value, offset, count, const_cast<T*>(values));
  }
  /// Reads a 1-D dataset of strings (fixed or variable length).
  std::vector<std::string> ReadStrings() const;
  /// Reads a block (hyperslab) into values (row-major, product of count elements).
  template <typename T>
  void ReadBlock(const std::vector<Size>& offset, const std::vector<Size>& count, T* values) const {
    const_cast<Dataset*>(this)->BlockRaw(false, ElementTypeOf<T>::value, offset, count, values);
  }

 private:
  /// NumElements(), refused (Error) when it times element_bytes exceeds kMaxReadBytes, so a
  /// damaged dataspace cannot make a reader allocate without bound.
  std::size_t CheckedCount(std::size_t element_bytes) const;
  void ReadRaw(ElementType type, void* values, std::size_t count) const;
  void WriteRaw(ElementType type, const void* values, std::size_t count);
  void BlockRaw(bool write, ElementType type, const std::vector<Size>& offset,
                const std::vector<Size>& count, void* values);
};

/// What a name in a group refers to. kLink: a soft or external link, which Kind never follows
/// (a table holds its data; a link could name a missing object, another file or a FIFO).
enum class LinkKind { kMissing, kGroup, kDataset, kLink, kOther };

/// Why a name of that kind is not the `what` ("group", "dataset") asked for.
std::string KindMismatch(LinkKind kind, const std::string& what);

/// A group; File is the root group of a file.
class Group : public Object {
 public:
  Group(Handle handle, std::string file, std::string path)
      : Object(std::move(handle), std::move(file), std::move(path)) {}

  /// Whether a direct child (no '/' in name) of that name exists, and what it is.
  LinkKind Kind(const std::string& name) const;
  bool Exists(const std::string& name) const { return Kind(name) != LinkKind::kMissing; }
  /// Names of the direct children, in creation order when the group tracks it (groups made by
  /// CreateGroup do), otherwise in name order.
  std::vector<std::string> MemberNames() const;

  Group OpenGroup(const std::string& name) const;
  /// Creates a child group that tracks creation order of its members.
  Group CreateGroup(const std::string& name);
  Dataset OpenDataset(const std::string& name) const;
  Dataset CreateDataset(const std::string& name, ElementType type, const std::vector<Size>& dims,
                        const DatasetOptions& options = {});
  template <typename T>
  Dataset CreateDataset(const std::string& name, const std::vector<Size>& dims,
                        const DatasetOptions& options = {}) {
    return CreateDataset(name, ElementTypeOf<T>::value, dims, options);
  }
  /// Creates a dataset and writes all of values into it.
  template <typename T>
  Dataset WriteDataset(const std::string& name, const std::vector<Size>& dims,
                       const std::vector<T>& values, const DatasetOptions& options = {}) {
    Dataset dataset = CreateDataset<T>(name, dims, options);
    dataset.Write(values);
    return dataset;
  }
  /// Creates a 1-D dataset of UTF-8 strings holding values (for messages and other texts too
  /// many for an attribute). The strings are stored fixed-length (as wide as the longest value,
  /// null-padded), because HDF5 cannot filter variable-length data: so deflate and fletcher32
  /// of options apply. Needs at least one value.
  Dataset WriteStringDataset(const std::string& name, const std::vector<std::string>& values,
                             const DatasetOptions& options = {});
  /// Unlinks a child (its storage is freed when no longer referenced).
  void Remove(const std::string& name);
};

/// On-disk format of a new file.
enum class FileFormat {
  /// HDF5 1.10's format (superblock 3, version-2 object headers): all metadata carries
  /// checksums, so a damaged header is a read error rather than a wrong number.
  kChecksummed,
  /// The earliest format HDF5 can write (no metadata checksums), what tables were written in
  /// before; kept so that readers of such files can be tested.
  kEarliest,
};

/// An open HDF5 file; also its root group "/".
class File : public Group {
 public:
  enum class Mode { kReadOnly, kReadWrite };

  /// Whether Open reads a file in HDF5's earliest format (kAllow only where a crash of HDF5 is
  /// contained: a child process, or tests of such files).
  enum class Earliest { kRefuse, kAllow };

  /// Opens an existing file after CheckSeal (seal.h): throws Error when it does not exist, is
  /// damaged (does not match its seal) or is not an HDF5 file, and EarliestFormatError for a
  /// file in HDF5's earliest format unless `earliest` allows it. A file opened for writing must
  /// be sealed again (SealFile) once closed.
  static File Open(const std::string& path, Mode mode = Mode::kReadOnly,
                   Earliest earliest = Earliest::kRefuse);
  /// Creates a file; with overwrite false, fails if the file exists. `sealed`: with an empty
  /// user block of kUserBlockSize bytes for SealFile to fill once the file is closed.
  static File Create(const std::string& path, bool overwrite = true,
                     FileFormat format = FileFormat::kChecksummed, bool sealed = false);

  /// Whether the file carried an intact seal when opened (false: an unsealed, older file).
  bool Sealed() const { return sealed_; }

  /// Writes buffered data to disk.
  void Flush();

 private:
  File(Handle handle, std::string file, bool sealed)
      : Group(std::move(handle), std::move(file), "/"), sealed_(sealed) {}
  bool sealed_ = false;
};

/// Copies every member of `source`'s root group (with everything below it, through H5Ocopy)
/// and every root attribute into `target`: a table in another file format, with variable-length
/// string attributes of the root rewritten fixed-length (fixed strings live in the object
/// header, which the checksummed format protects).
void CopyContents(const File& source, File* target);

}  // namespace wrc::h5
