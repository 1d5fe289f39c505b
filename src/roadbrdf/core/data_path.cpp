#include "roadbrdf/core/data_path.h"

#include <cstdlib>
#include <filesystem>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

std::string data_directory() {
  if (const char* env = std::getenv("ROADBRDF_DATA"); env != nullptr && *env != '\0') return env;
  return ROADBRDF_DATA_DIR;
}

std::string data_file(const std::string& relative) {
  const std::string path = data_directory() + "/" + relative;
  if (!std::filesystem::exists(path)) {
    throw InputError("bundled data file '" + path + "' not found (set ROADBRDF_DATA to the roadbrdf data/ folder)");
  }
  return path;
}

}  // namespace roadbrdf
