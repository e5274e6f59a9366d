// The flat table's writer and reader (flat_table.h). The digest is nettle's SHA-256 (Debian
// nettle-dev), the one the HDF5 table's seal uses: whatever the format, a table is proven intact
// by the same check before a byte of it is parsed.

#include "runtime/format/flat_table.h"

#include <fcntl.h>
#include <nettle/sha2.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "runtime/format/little_endian.h"
#include "wrc/runtime.hpp"

namespace wrc::format {
namespace {

// Longest axis or output name and unit: far beyond any real one, short enough that a damaged
// length cannot ask for much.
constexpr std::uint32_t kMaxNameBytes = 4096;
// Largest flat file read: 2^40 bytes (a TB), far above any table that fits a machine.
constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1} << 40;

// ---- writing ----------------------------------------------------------------------------------

using le::LoadUnsigned;
using le::PutF64;
using le::PutU32;
using le::PutU64;

void PutString(std::string& out, const std::string& text) {
  PutU32(out, static_cast<std::uint32_t>(text.size()));
  out += text;
}

std::array<std::uint8_t, SHA256_DIGEST_SIZE> Digest(std::string_view bytes) {
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(&context, digest.size(), digest.data());
  return digest;
}

// ---- reading ----------------------------------------------------------------------------------

// The body, read front to back: every read checks that the bytes are there, and names what it
// was reading when they are not.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::size_t at, std::string where)
      : bytes_(bytes), at_(at), where_(std::move(where)) {}

  std::size_t remaining() const { return bytes_.size() - at_; }
  std::size_t offset() const { return at_; }

  std::uint32_t U32(const std::string& what) {
    return static_cast<std::uint32_t>(LoadUnsigned(Take(4, what), 4));
  }
  std::uint64_t U64(const std::string& what) { return LoadUnsigned(Take(8, what), 8); }

  std::string String(std::uint64_t max_bytes, const std::string& what) {
    const std::uint32_t size = U32(what + "'s length");
    if (size > max_bytes) {
      Invalid(where_, what + " at byte " + std::to_string(at_ - 4) + " is " + std::to_string(size) +
                          " bytes long, more than " + std::to_string(max_bytes));
    }
    return std::string(Take(size, what), size);
  }

  void Doubles(std::uint64_t count, const std::string& what, std::vector<double>& out) {
    if (count > remaining() / 8) Truncated(count * 8, what);
    const char* p = Take(count * 8, what);
    out.reserve(count + kValuePadding);
    out.resize(count);
    for (std::uint64_t i = 0; i < count; ++i) {
      out[i] = le::LoadF64(p + 8 * i);
    }
  }

  const char* Take(std::uint64_t count, const std::string& what) {
    if (count > remaining()) Truncated(count, what);
    const char* p = bytes_.data() + at_;
    at_ += count;
    return p;
  }

  void Zero(std::uint64_t value, const std::string& what) {
    if (value != 0) Invalid(where_, what + " is " + std::to_string(value) + ", must be 0");
  }

  [[noreturn]] void Truncated(std::uint64_t count, const std::string& what) const {
    Invalid(where_, "truncated: " + what + " at byte " + std::to_string(at_) + " needs " +
                        std::to_string(count) + " bytes, " + std::to_string(remaining()) +
                        " remain");
  }

 private:
  std::string_view bytes_;
  std::size_t at_;
  std::string where_;
};

// The fixed header: magic, version, flags, size, digest, reserved.
std::uint32_t CheckHeader(std::string_view bytes, const std::string& where, bool check_digest) {
  if (bytes.size() < kFlatHeaderSize) {
    Invalid(where, "a flat table starts with a " + std::to_string(kFlatHeaderSize) +
                       "-byte header, the file has " + std::to_string(bytes.size()) + " bytes");
  }
  if (!IsFlatTable(bytes)) Invalid(where, "not a flat table (its first 8 bytes are not the magic)");
  const auto version = static_cast<std::uint32_t>(LoadUnsigned(bytes.data() + 8, 4));
  if (version < kFlatEarliestVersion || version > kFlatVersion) {
    Invalid(where, "flat table version " + std::to_string(version) +
                       ", this runtime reads versions " + std::to_string(kFlatEarliestVersion) +
                       " to " + std::to_string(kFlatVersion));
  }
  if (LoadUnsigned(bytes.data() + 12, 4) != 0)
    Invalid(where, "header flags set that no version defines");
  const std::uint64_t size = LoadUnsigned(bytes.data() + 16, 8);
  if (size != bytes.size()) {
    Invalid(where, "damaged: the header gives a size of " + std::to_string(size) +
                       " bytes, the file has " + std::to_string(bytes.size()) +
                       " (truncated, extended or edited)");
  }
  if (check_digest) {
    const auto digest = Digest(bytes.substr(kFlatDigestEnd));
    if (std::memcmp(digest.data(), bytes.data() + kFlatDigestOffset, digest.size()) != 0) {
      Invalid(where, "damaged: its bytes do not match their SHA-256 (a changed byte)");
    }
  }
  if (LoadUnsigned(bytes.data() + kFlatDigestEnd, 8) != 0)
    Invalid(where, "reserved header bytes set");
  return version;
}

void DecodeAttributes(Cursor& in, std::uint32_t count, TableContent& content,
                      const std::string& where) {
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string what = "attribute " + std::to_string(i);
    std::string key = in.String(kMaxNameBytes, what + "'s key");
    std::string value = in.String(in.remaining(), what + "'s value");
    if (key.empty()) Invalid(where, what + " has an empty key");
    if (!content.attributes.emplace(std::move(key), std::move(value)).second) {
      Invalid(where, what + " repeats a key");
    }
  }
}

void DecodeNumbers(Cursor& in, std::uint32_t count, TableContent& content,
                   const std::string& where) {
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string what = "number " + std::to_string(i);
    std::string key = in.String(kMaxNameBytes, what + "'s key");
    const double value = le::LoadF64(in.Take(8, what + "'s value"));
    if (key.empty()) Invalid(where, what + " has an empty key");
    if (!content.numbers.emplace(std::move(key), value).second) {
      Invalid(where, what + " repeats a key");
    }
  }
}

void DecodeAxes(Cursor& in, std::uint32_t count, TableContent& content) {
  for (std::uint32_t a = 0; a < count; ++a) {
    const std::string what = "axis " + std::to_string(a);
    AxisContent axis;
    axis.name = in.String(kMaxNameBytes, what + "'s name");
    axis.unit = in.String(kMaxNameBytes, what + "'s unit");
    const std::uint64_t nodes = in.U64(what + "'s node count");
    if (nodes == 0) Invalid(content.path + ":/axes/" + axis.name, "is empty");
    if (nodes > kMaxAxisNodes) {
      Invalid(content.path + ":/axes/" + axis.name,
              "has " + std::to_string(nodes) + " nodes, more than the " +
                  std::to_string(kMaxAxisNodes) + " a table axis may have");
    }
    in.Doubles(nodes, what + "'s nodes", axis.values);
    CheckAxisValues(axis.values, content.path + ":/axes/" + axis.name);
    content.axes.push_back(std::move(axis));
  }
}

void DecodeNodes(Cursor& in, TableContent& content, const std::string& where) {
  std::vector<std::uint64_t> shape;
  for (const AxisContent& axis : content.axes) shape.push_back(axis.values.size());
  const std::uint64_t nodes = CountNodes(shape, where + "/axes");
  const std::uint64_t outputs = content.outputs.size();
  while (in.offset() % 8 != 0)
    in.Zero(static_cast<std::uint8_t>(*in.Take(1, "padding")), "padding");
  if (outputs == 0) Invalid(where + "/outputs", "holds no outputs");
  if (nodes > in.remaining() / 8 / outputs) {
    Invalid(where, "truncated: the values of " + std::to_string(nodes) + " nodes and " +
                       std::to_string(outputs) + " outputs at byte " + std::to_string(in.offset()) +
                       " need more than the " + std::to_string(in.remaining()) +
                       " bytes that remain");
  }
  in.Doubles(nodes * outputs, "the values", content.values);
  const char* status = in.Take(nodes, "the status");
  content.status.assign(reinterpret_cast<const std::int8_t*>(status),
                        reinterpret_cast<const std::int8_t*>(status) + nodes);
  if (in.remaining() != 0) {
    Invalid(where,
            std::to_string(in.remaining()) + " bytes follow the status, where the file ends");
  }
}

}  // namespace

bool IsFlatTable(std::string_view leading) {
  return leading.size() >= kFlatMagic.size() &&
         std::memcmp(leading.data(), kFlatMagic.data(), kFlatMagic.size()) == 0;
}

bool IsFlatTableFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, kFlatMagic.size()> leading{};
  in.read(leading.data(), leading.size());
  return in && IsFlatTable(std::string_view(leading.data(), leading.size()));
}

std::string EncodeFlatTable(const TableContent& content) {
  std::string body;
  PutU32(body, static_cast<std::uint32_t>(content.attributes.size()));
  PutU32(body, static_cast<std::uint32_t>(content.axes.size()));
  PutU32(body, static_cast<std::uint32_t>(content.outputs.size()));
  PutU32(body, static_cast<std::uint32_t>(content.numbers.size()));
  for (const auto& [key, value] : content.attributes) {
    PutString(body, key);
    PutString(body, value);
  }
  for (const auto& [key, value] : content.numbers) {
    PutString(body, key);
    PutF64(body, value);
  }
  for (const AxisContent& axis : content.axes) {
    PutString(body, axis.name);
    PutString(body, axis.unit);
    PutU64(body, axis.values.size());
    for (const double v : axis.values) PutF64(body, v);
  }
  for (const OutputContent& output : content.outputs) {
    PutString(body, output.name);
    PutString(body, output.unit);
  }
  while ((kFlatHeaderSize + body.size()) % 8 != 0) body += '\0';
  body.reserve(body.size() + 8 * content.values.size() + content.status.size());
  for (const double v : content.values) PutF64(body, v);
  body.append(reinterpret_cast<const char*>(content.status.data()), content.status.size());

  std::string file(kFlatMagic.data(), kFlatMagic.size());
  PutU32(file, kFlatVersion);
  PutU32(file, 0);
  PutU64(file, kFlatHeaderSize + body.size());
  file.append(SHA256_DIGEST_SIZE, '\0');
  PutU64(file, 0);
  file += body;
  const auto digest = Digest(std::string_view(file).substr(kFlatDigestEnd));
  std::memcpy(file.data() + kFlatDigestOffset, digest.data(), digest.size());
  return file;
}

TableContent DecodeFlatTable(std::string_view bytes, const std::string& path, bool check_digest) {
  const std::string where = path + ":";
  const std::uint32_t version = CheckHeader(bytes, where, check_digest);
  TableContent content;
  content.path = path;
  Cursor in(bytes, kFlatHeaderSize, where);
  const std::uint32_t attributes = in.U32("the attribute count");
  const std::uint32_t axes = in.U32("the axis count");
  const std::uint32_t outputs = in.U32("the output count");
  const std::uint32_t numbers = in.U32("the number count");
  if (version < 2) in.Zero(numbers, "the reserved count");
  if (axes == 0 || axes > static_cast<std::uint32_t>(WRC_MAX_AXES)) {
    Invalid(where + "/axes",
            std::to_string(axes) + " axes, a table has 1 to " + std::to_string(WRC_MAX_AXES));
  }
  // Each output takes at least 8 bytes (two string lengths): a count beyond that is damage.
  if (outputs > in.remaining() / 8) in.Truncated(std::uint64_t{outputs} * 8, "the outputs");
  DecodeAttributes(in, attributes, content, where);
  DecodeNumbers(in, numbers, content, where);
  DecodeAxes(in, axes, content);
  for (std::uint32_t k = 0; k < outputs; ++k) {
    const std::string what = "output " + std::to_string(k);
    OutputContent output;
    output.name = in.String(kMaxNameBytes, what + "'s name");
    output.unit = in.String(kMaxNameBytes, what + "'s unit");
    content.outputs.push_back(std::move(output));
  }
  DecodeNodes(in, content, where);
  CheckContent(content, where);
  return content;
}

TableContent ReadFlatTable(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw TableError(WRC_ERR_FILE, path + ": cannot open: " + std::strerror(errno));
  std::string bytes;
  struct stat info {};
  std::string failure;
  if (::fstat(fd, &info) != 0) {
    failure = std::string("cannot read: ") + std::strerror(errno);
  } else if (static_cast<std::uint64_t>(info.st_size) > kMaxFileBytes) {
    failure = "larger than the " + std::to_string(kMaxFileBytes) + " bytes a flat table may have";
  } else {
    bytes.resize(static_cast<std::size_t>(info.st_size));
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        failure = got < 0 ? std::string("cannot read: ") + std::strerror(errno)
                          : "the file shrank while it was read";
        break;
      }
      done += static_cast<std::size_t>(got);
    }
  }
  ::close(fd);
  if (!failure.empty()) throw TableError(WRC_ERR_FILE, path + ": " + failure);
  return DecodeFlatTable(bytes, path);
}

void WriteFlatTable(const TableContent& content, const std::string& path) {
  const std::string bytes = EncodeFlatTable(content);
  const std::filesystem::path target(path);
  std::string temporary =
      (target.parent_path() / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) {
    throw TableError(WRC_ERR_FILE, path + ": cannot write beside it: " + std::strerror(errno));
  }
  std::size_t done = 0;
  std::string failure;
  while (done < bytes.size() && failure.empty()) {
    const ssize_t put = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) failure = std::string("cannot write: ") + std::strerror(errno);
    done += put > 0 ? static_cast<std::size_t>(put) : 0;
  }
  if (failure.empty() && ::fchmod(fd, 0644) != 0) failure = std::strerror(errno);
  if (failure.empty() && ::fsync(fd) != 0)
    failure = std::string("cannot flush: ") + std::strerror(errno);
  if (::close(fd) != 0 && failure.empty())
    failure = std::string("cannot close: ") + std::strerror(errno);
  if (failure.empty() && std::rename(temporary.c_str(), path.c_str()) != 0) {
    failure = std::string("cannot rename into place: ") + std::strerror(errno);
  }
  if (!failure.empty()) {
    ::unlink(temporary.c_str());
    throw TableError(WRC_ERR_FILE, path + ": " + failure);
  }
}

}  // namespace wrc::format
