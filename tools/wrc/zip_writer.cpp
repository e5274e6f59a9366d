#include "tools/wrc/zip_writer.h"

#include <sys/stat.h>
#include <zip.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "wrc/core/errors.h"

namespace wrc::cli {

ZipWriter::ZipWriter(std::string path) : path_(std::move(path)), temporary_(path_ + ".tmp") {
  int error = 0;
  archive_ = zip_open(temporary_.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (archive_ == nullptr) {
    zip_error_t e;
    zip_error_init_with_code(&e, error);
    const std::string message = zip_error_strerror(&e);
    zip_error_fini(&e);
    throw InputError(temporary_ + ": cannot create: " + message);
  }
}

ZipWriter::~ZipWriter() {
  if (archive_ != nullptr) zip_discard(archive_);
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void ZipWriter::Fail(const std::string& what) {
  throw InputError(temporary_ + ": " + what + ": " + zip_strerror(archive_));
}

void ZipWriter::Add(const std::string& name, std::string bytes, unsigned mode) {
  contents_.push_back(std::make_unique<std::string>(std::move(bytes)));
  const std::string& data = *contents_.back();
  zip_source_t* source = zip_source_buffer(archive_, data.data(), data.size(), 0);
  if (source == nullptr) Fail("cannot add " + name);
  const zip_int64_t index = zip_file_add(archive_, name.c_str(), source, ZIP_FL_ENC_UTF_8);
  if (index < 0) {
    zip_source_free(source);
    Fail("cannot add " + name);
  }
  const auto index_u = static_cast<zip_uint64_t>(index);
  if (zip_set_file_compression(archive_, index_u, ZIP_CM_DEFLATE, 0) != 0 ||
      zip_file_set_external_attributes(archive_, index_u, 0, ZIP_OPSYS_UNIX,
                                       (S_IFREG | mode) << 16) != 0) {
    Fail("cannot set the attributes of " + name);
  }
}

void ZipWriter::Close() {
  if (zip_close(archive_) != 0) Fail("cannot write the archive");
  archive_ = nullptr;
  contents_.clear();
  std::filesystem::rename(temporary_, path_);
}

}  // namespace wrc::cli
