#include "runtime/hdf5/hdf5.h"

#include "runtime/hdf5/seal.h"

// HDF5's own header: runtime/hdf5 is not an include directory, so <hdf5.h> cannot resolve to
// the wrapper header above.
#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <utility>

namespace wrc::h5 {

static_assert(std::is_same_v<Id, hid_t>, "wrc::h5::Id must be hid_t");
static_assert(std::is_same_v<Size, hsize_t>, "wrc::h5::Size must be hsize_t");

namespace {

// HDF5 prints its error stack to stderr on every failure unless told not to; the setting is
// per thread in thread-safe builds, so each thread switches it off before its first call.
void EnsureSilenced() {
  thread_local bool silenced = false;
  if (!silenced) {
    if (H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) < 0) {
      throw Error("(HDF5 library)", "cannot switch off HDF5's error printing");
    }
    silenced = true;
  }
}

// HDF5's innermost error description (the one that names the actual cause, e.g. "errno = 2,
// error message = 'No such file or directory'"), then clears the stack. Already on an error
// path: failures of these two calls leave the detail empty, nothing more to report.
std::string TakeHdf5Detail() {
  std::string detail;
  auto visit = [](unsigned /*depth*/, const H5E_error2_t* error, void* data) -> herr_t {
    auto* out = static_cast<std::string*>(data);
    *out = error->desc != nullptr ? error->desc : "";
    char minor[160] = {0};
    if (H5Eget_msg(error->min_num, nullptr, minor, sizeof minor) > 0 && minor[0] != '\0') {
      *out += out->empty() ? minor : std::string(" [") + minor + "]";
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, visit, &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

[[noreturn]] void Fail(const std::string& where, const std::string& what) {
  const std::string detail = TakeHdf5Detail();
  throw Error(where, detail.empty() ? what : what + " (HDF5: " + detail + ")");
}

// Every HDF5 return value goes through Check: negative means failure for hid_t, herr_t, htri_t
// and the ssize_t/int counts alike.
template <typename Result>
Result Check(Result result, const std::string& where, const char* what) {
  if (result < 0) Fail(where, what);
  return result;
}

std::string AttributeWhere(const std::string& object_where, const std::string& name) {
  return object_where + " attribute '" + name + "'";
}

// The HDF5 types of an element type: in memory, and on disk in both byte orders. Tables are
// written little-endian whatever the machine, so files are byte-identical across platforms.
struct TypesOf {
  hid_t native, little_endian, big_endian;
};

TypesOf HdfTypes(ElementType type) {
  switch (type) {
    case ElementType::kFloat64:
      return {H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, H5T_IEEE_F64BE};
    case ElementType::kFloat32:
      return {H5T_NATIVE_FLOAT, H5T_IEEE_F32LE, H5T_IEEE_F32BE};
    case ElementType::kInt8:
      return {H5T_NATIVE_INT8, H5T_STD_I8LE, H5T_STD_I8BE};
    case ElementType::kUInt8:
      return {H5T_NATIVE_UINT8, H5T_STD_U8LE, H5T_STD_U8BE};
    case ElementType::kInt32:
      return {H5T_NATIVE_INT32, H5T_STD_I32LE, H5T_STD_I32BE};
    case ElementType::kInt64:
      return {H5T_NATIVE_INT64, H5T_STD_I64LE, H5T_STD_I64BE};
  }
  return {H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, H5T_IEEE_F64BE};
}

hid_t NativeType(ElementType type) { return HdfTypes(type).native; }
hid_t FileType(ElementType type) { return HdfTypes(type).little_endian; }

// The standard file types of an element type, in both byte orders.
std::pair<hid_t, hid_t> StandardTypes(ElementType type) {
  const TypesOf t = HdfTypes(type);
  return {t.little_endian, t.big_endian};
}

constexpr ElementType kAllElementTypes[] = {ElementType::kFloat64, ElementType::kFloat32,
                                            ElementType::kInt8,    ElementType::kUInt8,
                                            ElementType::kInt32,   ElementType::kInt64};

std::size_t ElementBytes(ElementType type) {
  switch (type) {
    case ElementType::kFloat64:
    case ElementType::kInt64:
      return 8;
    case ElementType::kFloat32:
    case ElementType::kInt32:
      return 4;
    case ElementType::kInt8:
    case ElementType::kUInt8:
      return 1;
  }
  return 8;
}

// HDF5 clamps out-of-range values silently when converting between types; abort instead, so a
// value that does not fit the requested type is an error, never a wrong number.
H5T_conv_ret_t AbortOnLossyConversion(H5T_conv_except_t kind, hid_t, hid_t, void*, void*, void*) {
  if (kind == H5T_CONV_EXCEPT_RANGE_HI || kind == H5T_CONV_EXCEPT_RANGE_LOW ||
      kind == H5T_CONV_EXCEPT_TRUNCATE) {
    return H5T_CONV_ABORT;
  }
  return H5T_CONV_UNHANDLED;
}

Handle StrictTransferList(const std::string& where) {
  Handle dxpl(Check(H5Pcreate(H5P_DATASET_XFER), where, "cannot create a transfer property list"),
              Handle::Kind::kPropertyList);
  Check(H5Pset_type_conv_cb(dxpl.id(), AbortOnLossyConversion, nullptr), where,
        "cannot set the conversion callback");
  // Fletcher-32 is verified on read by default; said explicitly, as the data's integrity rests
  // on it.
  Check(H5Pset_edc_check(dxpl.id(), H5Z_ENABLE_EDC), where, "cannot enable checksum checks");
  return dxpl;
}

// Variable-length string type in memory with the character set of the stored type (HDF5 does
// not convert between ASCII and UTF-8).
Handle VariableStringType(H5T_cset_t cset, const std::string& where) {
  Handle type(Check(H5Tcopy(H5T_C_S1), where, "cannot copy the string type"),
              Handle::Kind::kDatatype);
  Check(H5Tset_size(type.id(), H5T_VARIABLE), where, "cannot make a variable-length string type");
  Check(H5Tset_cset(type.id(), cset), where, "cannot set the character set");
  return type;
}

void DeleteAttributeIfPresent(hid_t object, const std::string& name, const std::string& where) {
  if (Check(H5Aexists(object, name.c_str()), where, "cannot check for an attribute") > 0) {
    Check(H5Adelete(object, name.c_str()), where, "cannot delete the old attribute");
  }
}

// Chunk shape for a dataset that needs chunks (filters) but got none: the whole dataset, with
// the largest dimension halved until a chunk is at most 1 MiB (HDF5's chunk cache default).
std::vector<Size> AutomaticChunk(const std::vector<Size>& dims, std::size_t element_bytes) {
  std::vector<Size> chunk(dims.size());
  for (std::size_t i = 0; i < dims.size(); ++i) chunk[i] = std::max<Size>(dims[i], 1);
  const Size limit = Size{1} << 20;
  auto bytes = [&] {
    Size total = element_bytes;
    for (Size c : chunk) total *= c;
    return total;
  };
  while (bytes() > limit) {
    auto largest = std::max_element(chunk.begin(), chunk.end());
    if (*largest == 1) break;
    *largest = (*largest + 1) / 2;
  }
  return chunk;
}

std::vector<H5Z_filter_t> Filters(hid_t dataset, const std::string& where) {
  Handle dcpl(Check(H5Dget_create_plist(dataset), where, "cannot get the creation property list"),
              Handle::Kind::kPropertyList);
  const int count = Check(H5Pget_nfilters(dcpl.id()), where, "cannot count the filters");
  std::vector<H5Z_filter_t> filters;
  for (int i = 0; i < count; ++i) {
    unsigned flags = 0;
    std::size_t n_values = 0;
    unsigned config = 0;
    filters.push_back(Check(H5Pget_filter2(dcpl.id(), static_cast<unsigned>(i), &flags, &n_values,
                                           nullptr, 0, nullptr, &config),
                            where, "cannot query a filter"));
  }
  return filters;
}

}  // namespace

Error::Error(const std::string& object, const std::string& problem)
    : std::runtime_error(object + ": " + problem), object_(object) {}

void SkipLibraryTermination() {
  // Fails only when the library is already initialised; then there is nothing left to change.
  if (H5dont_atexit() < 0) H5Eclear2(H5E_DEFAULT);
}

std::unique_lock<std::recursive_mutex> LibraryLock() {
  static std::recursive_mutex mutex;
  return std::unique_lock<std::recursive_mutex>(mutex);
}

// ---------------------------------------------------------------------------------------------
// Handle

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    Reset();
    id_ = other.id_;
    kind_ = other.kind_;
    other.id_ = -1;
  }
  return *this;
}

void Handle::Reset() noexcept {
  if (id_ < 0) return;
  herr_t status = 0;
  switch (kind_) {
    case Kind::kFile:
      status = H5Fclose(id_);
      break;
    case Kind::kGroup:
      status = H5Gclose(id_);
      break;
    case Kind::kDataset:
      status = H5Dclose(id_);
      break;
    case Kind::kDataspace:
      status = H5Sclose(id_);
      break;
    case Kind::kAttribute:
      status = H5Aclose(id_);
      break;
    case Kind::kDatatype:
      status = H5Tclose(id_);
      break;
    case Kind::kPropertyList:
      status = H5Pclose(id_);
      break;
  }
  // A destructor cannot report a failed close; drop it so it does not pollute the next error.
  if (status < 0) H5Eclear2(H5E_DEFAULT);
  id_ = -1;
}

// ---------------------------------------------------------------------------------------------
// Dataspace, Datatype

Dataspace Dataspace::Simple(const std::vector<Size>& dims) {
  EnsureSilenced();
  const std::string where = "(new dataspace)";
  if (dims.empty()) {
    return Dataspace(Handle(Check(H5Screate(H5S_SCALAR), where, "cannot create a scalar space"),
                            Handle::Kind::kDataspace),
                     where);
  }
  return Dataspace(
      Handle(Check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), where,
                   "cannot create a dataspace"),
             Handle::Kind::kDataspace),
      where);
}

bool Dataspace::IsScalar() const {
  return Check(H5Sget_simple_extent_type(id()), where_, "cannot get the dataspace class") ==
         H5S_SCALAR;
}

int Dataspace::Rank() const {
  return Check(H5Sget_simple_extent_ndims(id()), where_, "cannot get the rank");
}

std::vector<Size> Dataspace::Dims() const {
  std::vector<Size> dims(static_cast<std::size_t>(Rank()));
  Check(H5Sget_simple_extent_dims(id(), dims.data(), nullptr), where_, "cannot get the dimensions");
  return dims;
}

Size Dataspace::NumElements() const {
  return static_cast<Size>(
      Check(H5Sget_simple_extent_npoints(id()), where_, "cannot count the elements"));
}

TypeClass Datatype::Class() const {
  switch (Check(H5Tget_class(id()), where_, "cannot get the type class")) {
    case H5T_INTEGER:
      return TypeClass::kInteger;
    case H5T_FLOAT:
      return TypeClass::kFloat;
    case H5T_STRING:
      return TypeClass::kString;
    default:
      return TypeClass::kOther;
  }
}

std::size_t Datatype::ElementSize() const {
  const std::size_t size = H5Tget_size(id());
  if (size == 0) Fail(where_, "cannot get the type size");
  return size;
}

std::string Datatype::Describe() const {
  const std::string bits = std::to_string(8 * ElementSize());
  switch (Class()) {
    case TypeClass::kInteger: {
      const H5T_sign_t sign = H5Tget_sign(id());
      if (sign == H5T_SGN_ERROR) Fail(where_, "cannot get the sign");
      return (sign == H5T_SGN_NONE ? "uint" : "int") + bits;
    }
    case TypeClass::kFloat:
      return "float" + bits;
    case TypeClass::kString:
      return "string";
    case TypeClass::kOther:
      break;
  }
  return "a non-numeric, non-string type";
}

bool Datatype::Is(ElementType type) const {
  const auto [little, big] = StandardTypes(type);
  return Check(H5Tequal(id(), little), where_, "cannot compare types") > 0 ||
         Check(H5Tequal(id(), big), where_, "cannot compare types") > 0;
}

bool Datatype::IsStandardNumeric() const {
  return std::any_of(std::begin(kAllElementTypes), std::end(kAllElementTypes),
                     [this](ElementType type) { return Is(type); });
}

namespace {

// Refuses a stored numeric type the wrapper does not know (see Datatype::IsStandardNumeric).
void RequireStandardNumeric(const Datatype& stored, const std::string& where) {
  if (stored.Class() != TypeClass::kInteger && stored.Class() != TypeClass::kFloat) {
    throw Error(where, "expected numbers, found " + stored.Describe());
  }
  if (!stored.IsStandardNumeric()) {
    throw Error(where, "stored type (" + stored.Describe() +
                           ") is not a standard IEEE float or integer: damaged or foreign file");
  }
}

// Refuses a read of count elements of bytes each above kMaxReadBytes.
void RequireReadable(Size count, std::size_t bytes, const std::string& where) {
  if (bytes == 0 || count > kMaxReadBytes / bytes) {
    throw Error(where, std::to_string(count) + " elements of " + std::to_string(bytes) +
                           " bytes are more than a table holds: damaged dataspace or datatype");
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Attribute

Datatype Attribute::Type() const {
  return Datatype(Handle(Check(H5Aget_type(handle_.id()), where_, "cannot get the type"),
                         Handle::Kind::kDatatype),
                  where_);
}

Dataspace Attribute::Space() const {
  return Dataspace(Handle(Check(H5Aget_space(handle_.id()), where_, "cannot get the dataspace"),
                          Handle::Kind::kDataspace),
                   where_);
}

std::vector<std::string> Attribute::ReadStrings() const {
  const Datatype stored = Type();
  if (stored.Class() != TypeClass::kString) {
    throw Error(where_, "expected a string, found " + stored.Describe());
  }
  const Dataspace space = Space();
  const auto count = static_cast<std::size_t>(space.NumElements());
  std::vector<std::string> values;
  values.reserve(count);
  if (Check(H5Tis_variable_str(stored.id()), where_, "cannot inspect the string type") > 0) {
    const H5T_cset_t cset = H5Tget_cset(stored.id());
    if (cset == H5T_CSET_ERROR) Fail(where_, "cannot get the character set");
    const Handle memory_type = VariableStringType(cset, where_);
    std::vector<char*> pointers(count, nullptr);
    Check(H5Aread(handle_.id(), memory_type.id(), pointers.data()), where_,
          "cannot read the strings");
    // HDF5 allocated the strings; free them even if copying throws.
    struct Reclaim {
      hid_t type, space;
      std::vector<char*>& pointers;
      ~Reclaim() {
        if (H5Dvlen_reclaim(type, space, H5P_DEFAULT, pointers.data()) < 0) H5Eclear2(H5E_DEFAULT);
      }
    } reclaim{memory_type.id(), space.id(), pointers};
    for (const char* p : pointers) values.emplace_back(p != nullptr ? p : "");
    return values;
  }
  const std::size_t width = stored.ElementSize();
  RequireReadable(count, width, where_);
  const H5T_str_t padding = H5Tget_strpad(stored.id());
  if (padding == H5T_STR_ERROR) Fail(where_, "cannot get the string padding");
  const Handle memory_type(Check(H5Tcopy(stored.id()), where_, "cannot copy the string type"),
                           Handle::Kind::kDatatype);
  std::vector<char> buffer(count * width);
  Check(H5Aread(handle_.id(), memory_type.id(), buffer.data()), where_, "cannot read the strings");
  for (std::size_t i = 0; i < count; ++i) {
    const char* begin = buffer.data() + i * width;
    std::size_t length = strnlen(begin, width);
    if (padding == H5T_STR_SPACEPAD) {
      while (length > 0 && begin[length - 1] == ' ') --length;
    }
    values.emplace_back(begin, length);
  }
  return values;
}

std::string Attribute::ReadString() const {
  if (Type().Class() == TypeClass::kString && Space().NumElements() != 1) {
    throw Error(where_, "expected one string, found " + std::to_string(Space().NumElements()));
  }
  return ReadStrings().front();
}

std::int64_t Attribute::ReadInt() const {
  const Datatype stored = Type();
  if (stored.Class() != TypeClass::kInteger) {
    throw Error(where_, "expected an integer, found " + stored.Describe());
  }
  RequireStandardNumeric(stored, where_);
  if (Space().NumElements() != 1) throw Error(where_, "expected a single integer");
  std::int64_t value = 0;
  Check(H5Aread(handle_.id(), H5T_NATIVE_INT64, &value), where_, "cannot read the integer");
  return value;
}

double Attribute::ReadDouble() const {
  const Datatype stored = Type();
  if (stored.Class() != TypeClass::kInteger && stored.Class() != TypeClass::kFloat) {
    throw Error(where_, "expected a number, found " + stored.Describe());
  }
  RequireStandardNumeric(stored, where_);
  if (Space().NumElements() != 1) throw Error(where_, "expected a single number");
  double value = 0.0;
  Check(H5Aread(handle_.id(), H5T_NATIVE_DOUBLE, &value), where_, "cannot read the number");
  return value;
}

// ---------------------------------------------------------------------------------------------
// Object

std::string Object::ChildPath(const std::string& name) const {
  return path_ == "/" ? "/" + name : path_ + "/" + name;
}

bool Object::HasAttribute(const std::string& name) const {
  EnsureSilenced();
  return Check(H5Aexists(id(), name.c_str()), Where(), "cannot check for an attribute") > 0;
}

Attribute Object::OpenAttribute(const std::string& name) const {
  const std::string where = AttributeWhere(Where(), name);
  if (!HasAttribute(name)) throw Error(where, "missing");
  return Attribute(Handle(Check(H5Aopen(id(), name.c_str(), H5P_DEFAULT), where, "cannot open"),
                          Handle::Kind::kAttribute),
                   where);
}

std::vector<std::string> Object::AttributeNames() const {
  EnsureSilenced();
  std::vector<std::string> names;
  auto visit = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  Check(H5Aiterate2(id(), H5_INDEX_NAME, H5_ITER_INC, nullptr, visit, &names), Where(),
        "cannot list the attributes");
  return names;
}

void Object::RemoveAttribute(const std::string& name) {
  EnsureSilenced();
  Check(H5Adelete(id(), name.c_str()), AttributeWhere(Where(), name), "cannot delete");
}

namespace {

// Creates attribute `name` on object (replacing one of that name) holding the strings, as a
// scalar when `scalar`, else as a 1-D array.
void WriteStrings(hid_t object, const std::string& name, const std::vector<std::string>& values,
                  bool scalar, StringStorage storage, const std::string& where) {
  DeleteAttributeIfPresent(object, name, where);
  Handle type;
  std::vector<const char*> pointers;
  std::vector<char> fixed;
  const void* buffer = nullptr;
  if (storage == StringStorage::kVariable) {
    type = VariableStringType(H5T_CSET_UTF8, where);
    for (const std::string& value : values) pointers.push_back(value.c_str());
    buffer = pointers.data();
  } else {
    std::size_t width = 1;  // HDF5 has no zero-size string type.
    for (const std::string& value : values) width = std::max(width, value.size());
    type = Handle(Check(H5Tcopy(H5T_C_S1), where, "cannot copy the string type"),
                  Handle::Kind::kDatatype);
    Check(H5Tset_size(type.id(), width), where, "cannot set the string size");
    Check(H5Tset_strpad(type.id(), H5T_STR_NULLPAD), where, "cannot set the string padding");
    Check(H5Tset_cset(type.id(), H5T_CSET_UTF8), where, "cannot set the character set");
    fixed.assign(width * values.size(), '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::copy(values[i].begin(), values[i].end(), fixed.begin() + static_cast<long>(i * width));
    }
    buffer = fixed.data();
  }
  const Dataspace space =
      scalar ? Dataspace::Simple({}) : Dataspace::Simple({static_cast<Size>(values.size())});
  const Handle attribute(
      Check(H5Acreate2(object, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
            where, "cannot create"),
      Handle::Kind::kAttribute);
  Check(H5Awrite(attribute.id(), type.id(), buffer), where, "cannot write");
}

}  // namespace

void Object::WriteStringAttribute(const std::string& name, std::string_view value,
                                  StringStorage storage) {
  EnsureSilenced();
  WriteStrings(id(), name, {std::string(value)}, /*scalar=*/true, storage,
               AttributeWhere(Where(), name));
}

void Object::WriteStringArrayAttribute(const std::string& name,
                                       const std::vector<std::string>& values,
                                       StringStorage storage) {
  EnsureSilenced();
  WriteStrings(id(), name, values, /*scalar=*/false, storage, AttributeWhere(Where(), name));
}

void Object::WriteIntAttribute(const std::string& name, std::int64_t value) {
  EnsureSilenced();
  const std::string where = AttributeWhere(Where(), name);
  DeleteAttributeIfPresent(id(), name, where);
  const Dataspace space = Dataspace::Simple({});
  const Handle attribute(
      Check(H5Acreate2(id(), name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
            where, "cannot create"),
      Handle::Kind::kAttribute);
  Check(H5Awrite(attribute.id(), H5T_NATIVE_INT64, &value), where, "cannot write");
}

void Object::WriteDoubleAttribute(const std::string& name, double value) {
  EnsureSilenced();
  const std::string where = AttributeWhere(Where(), name);
  DeleteAttributeIfPresent(id(), name, where);
  const Dataspace space = Dataspace::Simple({});
  const Handle attribute(
      Check(H5Acreate2(id(), name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
            where, "cannot create"),
      Handle::Kind::kAttribute);
  Check(H5Awrite(attribute.id(), H5T_NATIVE_DOUBLE, &value), where, "cannot write");
}

// ---------------------------------------------------------------------------------------------
// Dataset

Dataspace Dataset::Space() const {
  return Dataspace(Handle(Check(H5Dget_space(id()), Where(), "cannot get the dataspace"),
                          Handle::Kind::kDataspace),
                   Where());
}

Datatype Dataset::Type() const {
  return Datatype(
      Handle(Check(H5Dget_type(id()), Where(), "cannot get the type"), Handle::Kind::kDatatype),
      Where());
}

std::vector<Size> Dataset::ChunkShape() const {
  const std::string where = Where();
  Handle dcpl(Check(H5Dget_create_plist(id()), where, "cannot get the creation property list"),
              Handle::Kind::kPropertyList);
  if (Check(H5Pget_layout(dcpl.id()), where, "cannot get the layout") != H5D_CHUNKED) return {};
  std::vector<Size> chunk(static_cast<std::size_t>(Space().Rank()));
  Check(H5Pget_chunk(dcpl.id(), static_cast<int>(chunk.size()), chunk.data()), where,
        "cannot get the chunk shape");
  return chunk;
}

bool Dataset::HasDeflate() const {
  const auto filters = Filters(id(), Where());
  return std::find(filters.begin(), filters.end(), H5Z_FILTER_DEFLATE) != filters.end();
}

bool Dataset::HasFletcher32() const {
  const auto filters = Filters(id(), Where());
  return std::find(filters.begin(), filters.end(), H5Z_FILTER_FLETCHER32) != filters.end();
}

std::size_t Dataset::CheckedCount(std::size_t element_bytes) const {
  const Size count = NumElements();
  RequireReadable(count, element_bytes, Where());
  return static_cast<std::size_t>(count);
}

void Dataset::CheckFilters() const {
  const std::string where = Where();
  Handle dcpl(Check(H5Dget_create_plist(id()), where, "cannot get the creation property list"),
              Handle::Kind::kPropertyList);
  const int count = Check(H5Pget_nfilters(dcpl.id()), where, "cannot count the filters");
  const std::size_t element_bytes = Type().ElementSize();
  for (int i = 0; i < count; ++i) {
    unsigned flags = 0;
    std::size_t n_values = 4;
    unsigned values[4] = {0, 0, 0, 0};
    unsigned config = 0;
    const H5Z_filter_t filter = Check(H5Pget_filter2(dcpl.id(), static_cast<unsigned>(i), &flags,
                                                     &n_values, values, 0, nullptr, &config),
                                      where, "cannot query a filter");
    const bool fits =
        (filter == H5Z_FILTER_SHUFFLE && n_values == 1 && values[0] == element_bytes) ||
        (filter == H5Z_FILTER_DEFLATE && n_values == 1 && values[0] <= 9) ||
        (filter == H5Z_FILTER_FLETCHER32 && n_values == 0);
    if (!fits) {
      throw Error(where, "filter " + std::to_string(i) + " (id " + std::to_string(filter) + ", " +
                             std::to_string(n_values) +
                             " parameters) is not shuffle, deflate or fletcher32 with parameters "
                             "that fit the stored type: damaged or foreign file");
    }
  }
}

void Dataset::ReadRaw(ElementType type, void* values, std::size_t count) const {
  EnsureSilenced();
  const std::string where = Where();
  RequireStandardNumeric(Type(), where);
  CheckFilters();
  if (count != NumElements()) throw Error(where, "element count does not match the buffer");
  const Handle dxpl = StrictTransferList(where);
  Check(H5Dread(id(), NativeType(type), H5S_ALL, H5S_ALL, dxpl.id(), values), where,
        "cannot read (or a value does not fit the requested type)");
}

void Dataset::WriteRaw(ElementType type, const void* values, std::size_t count) {
  EnsureSilenced();
  const std::string where = Where();
  if (count != NumElements()) {
    throw Error(where, "writing " + std::to_string(count) + " values into a dataset of " +
                           std::to_string(NumElements()));
  }
  const Handle dxpl = StrictTransferList(where);
  Check(H5Dwrite(id(), NativeType(type), H5S_ALL, H5S_ALL, dxpl.id(), values), where,
        "cannot write (or a value does not fit the stored type)");
}

void Dataset::BlockRaw(bool write, ElementType type, const std::vector<Size>& offset,
                       const std::vector<Size>& count, void* values) {
  EnsureSilenced();
  const std::string where = Where();
  const Dataspace file_space = Space();
  const std::vector<Size> dims = file_space.Dims();
  if (offset.size() != dims.size() || count.size() != dims.size()) {
    throw Error(where, "block rank does not match the dataset rank " + std::to_string(dims.size()));
  }
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (offset[i] + count[i] > dims[i]) {
      throw Error(where, "block exceeds the dataset in dimension " + std::to_string(i));
    }
  }
  Check(H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, offset.data(), nullptr, count.data(),
                            nullptr),
        where, "cannot select the block");
  if (!write) {
    RequireStandardNumeric(Type(), where);
    CheckFilters();
  }
  const Dataspace memory_space = Dataspace::Simple(count);
  const Handle dxpl = StrictTransferList(where);
  if (write) {
    Check(H5Dwrite(id(), NativeType(type), memory_space.id(), file_space.id(), dxpl.id(), values),
          where, "cannot write the block");
  } else {
    Check(H5Dread(id(), NativeType(type), memory_space.id(), file_space.id(), dxpl.id(), values),
          where, "cannot read the block");
  }
}

// ---------------------------------------------------------------------------------------------
// Group

std::string KindMismatch(LinkKind kind, const std::string& what) {
  switch (kind) {
    case LinkKind::kMissing:
      return "missing (no such " + what + ")";
    case LinkKind::kLink:
      return "a soft or external link, not a " + what + " stored in the file";
    default:
      return "not a " + what;
  }
}

LinkKind Group::Kind(const std::string& name) const {
  EnsureSilenced();
  if (name.empty() || name.find('/') != std::string::npos) {
    throw Error(ChildPath(name), "not a direct child name");
  }
  if (Check(H5Lexists(id(), name.c_str(), H5P_DEFAULT), Where(), "cannot check for a link") <= 0) {
    return LinkKind::kMissing;
  }
  H5L_info_t link{};
  Check(H5Lget_info(id(), name.c_str(), &link, H5P_DEFAULT), Where(), "cannot inspect a link");
  if (link.type != H5L_TYPE_HARD) return LinkKind::kLink;
  const hid_t object = H5Oopen(id(), name.c_str(), H5P_DEFAULT);
  if (object < 0) {
    H5Eclear2(H5E_DEFAULT);
    return LinkKind::kOther;
  }
  const H5I_type_t type = H5Iget_type(object);
  if (H5Oclose(object) < 0) H5Eclear2(H5E_DEFAULT);
  if (type == H5I_GROUP) return LinkKind::kGroup;
  if (type == H5I_DATASET) return LinkKind::kDataset;
  return LinkKind::kOther;
}

std::vector<std::string> Group::MemberNames() const {
  EnsureSilenced();
  const std::string where = Where();
  // A File's identifier is a file, not a group; its creation flags live on the root group.
  Handle root;
  hid_t group = id();
  if (H5Iget_type(id()) == H5I_FILE) {
    root = Handle(Check(H5Gopen2(id(), "/", H5P_DEFAULT), where, "cannot open the root group"),
                  Handle::Kind::kGroup);
    group = root.id();
  }
  Handle gcpl(Check(H5Gget_create_plist(group), where, "cannot get the creation property list"),
              Handle::Kind::kPropertyList);
  unsigned order_flags = 0;
  Check(H5Pget_link_creation_order(gcpl.id(), &order_flags), where,
        "cannot get the creation-order flags");
  const H5_index_t index =
      (order_flags & H5P_CRT_ORDER_TRACKED) != 0 ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  std::vector<std::string> names;
  auto visit = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  Check(H5Literate(id(), index, H5_ITER_INC, nullptr, visit, &names), where,
        "cannot list the members");
  return names;
}

namespace {

// A dataset's values must be in the file, in contiguous or chunked storage: external storage
// (raw data in other files, even /dev/zero or a FIFO) and virtual datasets (mapped from other
// datasets, filled silently where a source is missing) would give numbers the file's checksums
// and seal never saw.
void RequireStoredInFile(hid_t dataset, const std::string& where) {
  const Handle plist(Check(H5Dget_create_plist(dataset), where, "cannot get the creation list"),
                     Handle::Kind::kPropertyList);
  const H5D_layout_t layout = H5Pget_layout(plist.id());
  if (layout != H5D_CONTIGUOUS && layout != H5D_CHUNKED) {
    Fail(where, layout == H5D_VIRTUAL ? "a virtual dataset, not values stored in the file"
                                      : "storage other than contiguous or chunked");
  }
  if (Check(H5Pget_external_count(plist.id()), where, "cannot inspect the storage") > 0) {
    Fail(where, "external storage (its values in other files), not values stored in the file");
  }
}

}  // namespace

Group Group::OpenGroup(const std::string& name) const {
  EnsureSilenced();
  const std::string path = ChildPath(name);
  const std::string where = file_ + ":" + path;
  const LinkKind kind = Kind(name);
  if (kind != LinkKind::kGroup) throw Error(where, KindMismatch(kind, "group"));
  return Group(Handle(Check(H5Gopen2(id(), name.c_str(), H5P_DEFAULT), where, "cannot open group"),
                      Handle::Kind::kGroup),
               file_, path);
}

Group Group::CreateGroup(const std::string& name) {
  EnsureSilenced();
  const std::string path = ChildPath(name);
  const std::string where = file_ + ":" + path;
  Handle gcpl(Check(H5Pcreate(H5P_GROUP_CREATE), where, "cannot create a property list"),
              Handle::Kind::kPropertyList);
  Check(H5Pset_link_creation_order(gcpl.id(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), where,
        "cannot track creation order");
  return Group(Handle(Check(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, gcpl.id(), H5P_DEFAULT),
                            where, "cannot create group"),
                      Handle::Kind::kGroup),
               file_, path);
}

Dataset Group::OpenDataset(const std::string& name) const {
  EnsureSilenced();
  const std::string path = ChildPath(name);
  const std::string where = file_ + ":" + path;
  const LinkKind kind = Kind(name);
  if (kind != LinkKind::kDataset) throw Error(where, KindMismatch(kind, "dataset"));
  Dataset dataset(
      Handle(Check(H5Dopen2(id(), name.c_str(), H5P_DEFAULT), where, "cannot open dataset"),
             Handle::Kind::kDataset),
      file_, path);
  RequireStoredInFile(dataset.id(), where);
  return dataset;
}

Dataset Group::CreateDataset(const std::string& name, ElementType type,
                             const std::vector<Size>& dims, const DatasetOptions& options) {
  EnsureSilenced();
  const std::string path = ChildPath(name);
  const std::string where = file_ + ":" + path;
  const Dataspace space = Dataspace::Simple(dims);
  Handle dcpl(Check(H5Pcreate(H5P_DATASET_CREATE), where, "cannot create a property list"),
              Handle::Kind::kPropertyList);
  Size n_elements = 1;
  for (Size d : dims) n_elements *= d;
  const bool filtered = options.deflate_level >= 0 || options.shuffle || options.fletcher32;
  std::vector<Size> chunk = options.chunk;
  // Chunks (and so filters) need a non-empty, non-scalar dataset.
  if (chunk.empty() && filtered && !dims.empty() && n_elements > 0) {
    chunk = AutomaticChunk(dims, ElementBytes(type));
  }
  if (!chunk.empty()) {
    if (chunk.size() != dims.size()) throw Error(where, "chunk rank differs from dataset rank");
    for (std::size_t i = 0; i < dims.size(); ++i) {
      if (chunk[i] == 0 || chunk[i] > std::max<Size>(dims[i], 1)) {
        throw Error(where, "chunk dimension " + std::to_string(i) + " must be in 1..size");
      }
    }
    Check(H5Pset_chunk(dcpl.id(), static_cast<int>(chunk.size()), chunk.data()), where,
          "cannot set the chunk shape");
    // Pipeline order: shuffle helps deflate; the checksum covers the bytes as stored.
    if (options.shuffle) Check(H5Pset_shuffle(dcpl.id()), where, "cannot add shuffle");
    if (options.deflate_level >= 0) {
      if (Check(H5Zfilter_avail(H5Z_FILTER_DEFLATE), where, "cannot query filters") <= 0) {
        throw Error(where, "this HDF5 library has no deflate filter");
      }
      Check(H5Pset_deflate(dcpl.id(), static_cast<unsigned>(std::min(options.deflate_level, 9))),
            where, "cannot add deflate");
    }
    if (options.fletcher32) Check(H5Pset_fletcher32(dcpl.id()), where, "cannot add fletcher32");
  }
  return Dataset(Handle(Check(H5Dcreate2(id(), name.c_str(), FileType(type), space.id(),
                                         H5P_DEFAULT, dcpl.id(), H5P_DEFAULT),
                              where, "cannot create dataset"),
                        Handle::Kind::kDataset),
                 file_, path);
}

void Group::Remove(const std::string& name) {
  EnsureSilenced();
  Check(H5Ldelete(id(), name.c_str(), H5P_DEFAULT), file_ + ":" + ChildPath(name), "cannot remove");
}

// ---------------------------------------------------------------------------------------------
// File

File File::Open(const std::string& path, Mode mode, Earliest earliest) {
  EnsureSilenced();
  const SealStatus seal = CheckSeal(path);
  if (seal == SealStatus::kUnsealedEarliest && earliest == Earliest::kRefuse) {
    throw EarliestFormatError(
        path + ":/",
        "written in HDF5's earliest format, whose metadata carries no checksums (a damaged "
        "byte can crash the HDF5 library as it reads): convert it once with `wrc upgrade " +
            path + " -o NEW.h5`, which reads it in a separate process");
  }
  const bool sealed = seal == SealStatus::kIntact;
  const unsigned flags = mode == Mode::kReadOnly ? H5F_ACC_RDONLY : H5F_ACC_RDWR;
  return File(Handle(Check(H5Fopen(path.c_str(), flags, H5P_DEFAULT), path + ":/",
                           "cannot open the file as HDF5"),
                     Handle::Kind::kFile),
              path, sealed);
}

File File::Create(const std::string& path, bool overwrite, FileFormat format, bool sealed) {
  EnsureSilenced();
  const std::string where = path + ":/";
  Handle fapl(Check(H5Pcreate(H5P_FILE_ACCESS), where, "cannot create a property list"),
              Handle::Kind::kPropertyList);
  if (format == FileFormat::kChecksummed) {
    Check(H5Pset_libver_bounds(fapl.id(), H5F_LIBVER_V110, H5F_LIBVER_V110), where,
          "cannot select the HDF5 1.10 file format");
  }
  Handle fcpl(Check(H5Pcreate(H5P_FILE_CREATE), where, "cannot create a property list"),
              Handle::Kind::kPropertyList);
  // The root group keeps its members in creation order too, like groups from CreateGroup.
  Check(H5Pset_link_creation_order(fcpl.id(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), where,
        "cannot track creation order");
  if (sealed) {
    Check(H5Pset_userblock(fcpl.id(), kUserBlockSize), where, "cannot reserve the user block");
  }
  const unsigned flags = overwrite ? H5F_ACC_TRUNC : H5F_ACC_EXCL;
  return File(Handle(Check(H5Fcreate(path.c_str(), flags, fcpl.id(), fapl.id()), where,
                           "cannot create the file"),
                     Handle::Kind::kFile),
              path, false);
}

void File::Flush() { Check(H5Fflush(id(), H5F_SCOPE_GLOBAL), Where(), "cannot flush"); }

namespace {

// A root attribute of a fixed-size, non-string type, byte for byte through its native type.
void CopyNumericAttribute(const Attribute& attribute, const std::string& name, File* target) {
  const std::string& where = attribute.Where();
  const Handle stored(Check(H5Aget_type(attribute.id()), where, "cannot get the type"),
                      Handle::Kind::kDatatype);
  if (Check(H5Tdetect_class(stored.id(), H5T_VLEN), where, "cannot inspect the type") > 0) {
    Fail(where, "an attribute of variable-length type, which no table carries");
  }
  const Handle native(
      Check(H5Tget_native_type(stored.id(), H5T_DIR_ASCEND), where, "cannot get a native type"),
      Handle::Kind::kDatatype);
  const Dataspace space = attribute.Space();
  const auto count = static_cast<std::size_t>(space.NumElements());
  const std::size_t width = H5Tget_size(native.id());
  RequireReadable(count, width, where);
  std::vector<unsigned char> buffer(count * width);
  Check(H5Aread(attribute.id(), native.id(), buffer.data()), where, "cannot read");
  const std::string target_where = AttributeWhere(target->Where(), name);
  const Handle copy(Check(H5Acreate2(target->id(), name.c_str(), stored.id(), space.id(),
                                     H5P_DEFAULT, H5P_DEFAULT),
                          target_where, "cannot create"),
                    Handle::Kind::kAttribute);
  Check(H5Awrite(copy.id(), native.id(), buffer.data()), target_where, "cannot write");
}

}  // namespace

void CopyContents(const File& source, File* target) {
  EnsureSilenced();
  for (const std::string& name : source.AttributeNames()) {
    const Attribute attribute = source.OpenAttribute(name);
    if (attribute.Type().Class() != TypeClass::kString) {
      CopyNumericAttribute(attribute, name, target);
    } else if (attribute.Space().Rank() == 0) {
      target->WriteStringAttribute(name, attribute.ReadString());
    } else {
      target->WriteStringArrayAttribute(name, attribute.ReadStrings());
    }
  }
  for (const std::string& name : source.MemberNames()) {
    Check(H5Ocopy(source.id(), name.c_str(), target->id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          source.Where() + name, "cannot copy");
  }
}

}  // namespace wrc::h5

// ---------------------------------------------------------------------------------------------
// String datasets (1-D)

namespace wrc::h5 {
namespace {

// Creation property list for a 1-D dataset of n strings of `width` bytes: chunked (at most about
// 1 MiB per chunk) with the requested deflate and fletcher32; shuffle does not help text.
Handle StringDatasetCreationList(Size n, std::size_t width, const DatasetOptions& options,
                                 const std::string& where) {
  Handle dcpl(Check(H5Pcreate(H5P_DATASET_CREATE), where, "cannot create a property list"),
              Handle::Kind::kPropertyList);
  const bool filtered = options.deflate_level >= 0 || options.fletcher32;
  if (!filtered && options.chunk.empty()) return dcpl;
  const Size automatic = std::max<Size>(1, (Size{1} << 20) / std::max<std::size_t>(width, 1));
  const Size chunk = options.chunk.empty() ? std::min<Size>(n, automatic) : options.chunk.front();
  if (options.chunk.size() > 1 || chunk == 0 || chunk > n) {
    throw Error(where, "chunk of a 1-D string dataset must be one dimension in 1..size");
  }
  Check(H5Pset_chunk(dcpl.id(), 1, &chunk), where, "cannot set the chunk shape");
  if (options.deflate_level >= 0) {
    Check(H5Pset_deflate(dcpl.id(), static_cast<unsigned>(std::min(options.deflate_level, 9))),
          where, "cannot add deflate");
  }
  if (options.fletcher32) Check(H5Pset_fletcher32(dcpl.id()), where, "cannot add fletcher32");
  return dcpl;
}

}  // namespace

Dataset Group::WriteStringDataset(const std::string& name, const std::vector<std::string>& values,
                                  const DatasetOptions& options) {
  EnsureSilenced();
  const std::string path = ChildPath(name);
  const std::string where = file_ + ":" + path;
  if (values.empty()) throw Error(where, "a string dataset needs at least one value");
  std::size_t width = 1;  // HDF5 string types cannot be 0 bytes wide
  for (const std::string& value : values) width = std::max(width, value.size());
  Handle type(Check(H5Tcopy(H5T_C_S1), where, "cannot copy the string type"),
              Handle::Kind::kDatatype);
  Check(H5Tset_size(type.id(), width), where, "cannot set the string width");
  Check(H5Tset_strpad(type.id(), H5T_STR_NULLPAD), where, "cannot set the string padding");
  Check(H5Tset_cset(type.id(), H5T_CSET_UTF8), where, "cannot set the character set");
  const Size n = values.size();
  const Dataspace space = Dataspace::Simple({n});
  const Handle dcpl = StringDatasetCreationList(n, width, options, where);
  Dataset dataset(Handle(Check(H5Dcreate2(id(), name.c_str(), type.id(), space.id(), H5P_DEFAULT,
                                          dcpl.id(), H5P_DEFAULT),
                               where, "cannot create dataset"),
                         Handle::Kind::kDataset),
                  file_, path);
  std::vector<char> buffer(values.size() * width, '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::copy(values[i].begin(), values[i].end(), buffer.begin() + static_cast<long>(i * width));
  }
  Check(H5Dwrite(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), where,
        "cannot write the strings");
  return dataset;
}

std::vector<std::string> Dataset::ReadStrings() const {
  EnsureSilenced();
  const std::string where = Where();
  const Datatype stored = Type();
  if (stored.Class() != TypeClass::kString) {
    throw Error(where, "expected strings, found " + stored.Describe());
  }
  const Dataspace space = Space();
  if (space.Rank() != 1) throw Error(where, "expected a 1-D dataset of strings");
  const auto count = static_cast<std::size_t>(space.NumElements());
  std::vector<std::string> values;
  values.reserve(count);
  if (Check(H5Tis_variable_str(stored.id()), where, "cannot inspect the string type") > 0) {
    const H5T_cset_t cset = H5Tget_cset(stored.id());
    if (cset == H5T_CSET_ERROR) Fail(where, "cannot get the character set");
    const Handle memory_type = VariableStringType(cset, where);
    std::vector<char*> pointers(count, nullptr);
    Check(H5Dread(id(), memory_type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), where,
          "cannot read the strings");
    // HDF5 allocated the strings; free them even if copying throws.
    struct Reclaim {
      hid_t type, space;
      std::vector<char*>& pointers;
      ~Reclaim() {
        if (H5Dvlen_reclaim(type, space, H5P_DEFAULT, pointers.data()) < 0) H5Eclear2(H5E_DEFAULT);
      }
    } reclaim{memory_type.id(), space.id(), pointers};
    for (const char* p : pointers) values.emplace_back(p != nullptr ? p : "");
    return values;
  }
  const std::size_t width = stored.ElementSize();
  RequireReadable(count, width, where);
  const Handle memory_type(Check(H5Tcopy(stored.id()), where, "cannot copy the string type"),
                           Handle::Kind::kDatatype);
  std::vector<char> buffer(count * width);
  Check(H5Dread(id(), memory_type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), where,
        "cannot read the strings");
  for (std::size_t i = 0; i < count; ++i) {
    const char* begin = buffer.data() + i * width;
    values.emplace_back(begin, strnlen(begin, width));
  }
  return values;
}

}  // namespace wrc::h5
