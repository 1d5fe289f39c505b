#include "roadbrdf/core/data_path.h"

#include <dlfcn.h>

#include <cstdlib>
#include <system_error>

#include "roadbrdf/core/error.h"

namespace roadbrdf {

namespace fs = std::filesystem;

namespace {

// Ancestors of the image folder that are searched (the Python extension sits four levels below
// the prefix: P/lib/python3/dist-packages/roadbrdf).
constexpr int kAncestorLevels = 6;

bool directory_exists(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

}  // namespace

fs::path image_directory() {
  std::error_code ec;
  Dl_info info{};
  // A shared object (the Python extension) reports its own file; for the main program dladdr may
  // report argv[0], so the kernel's /proc/self/exe is used instead.
  if (dladdr(reinterpret_cast<void*>(&image_directory), &info) != 0 && info.dli_fname != nullptr) {
    const fs::path file = info.dli_fname;
    if (file.filename().string().find(".so") != std::string::npos) {
      const fs::path canonical = fs::weakly_canonical(file, ec);
      if (!ec) return canonical.parent_path();
    }
  }
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) return exe.parent_path();
  return fs::current_path(ec);
}

std::string data_directory() {
  if (const char* env = std::getenv("ROADBRDF_DATA"); env != nullptr && *env != '\0') return env;
  fs::path dir = image_directory();
  for (int level = 0; level <= kAncestorLevels && !dir.empty(); ++level) {
    const fs::path candidate = dir / "share" / "roadbrdf" / "data";
    if (directory_exists(candidate)) return candidate.string();
    if (dir == dir.root_path()) break;
    dir = dir.parent_path();
  }
  throw InputError("the bundled data folder share/roadbrdf/data was not found next to " + image_directory().string() +
                   " (set ROADBRDF_DATA to the data/ folder of roadbrdf)");
}

std::string data_file(const std::string& relative) {
  std::string path = data_directory() + "/" + relative;
  if (!fs::exists(path)) {
    throw InputError("bundled data file '" + path + "' not found (set ROADBRDF_DATA to the roadbrdf data/ folder)");
  }
  return path;
}

std::string python_package_parent() {
  fs::path dir = image_directory();
  for (int level = 0; level <= kAncestorLevels && !dir.empty(); ++level) {
    for (const fs::path& candidate : {dir / "python", dir / ROADBRDF_INSTALL_PYTHONDIR}) {
      if (fs::exists(candidate / "roadbrdf" / "__init__.py")) return candidate.string();
    }
    if (dir == dir.root_path()) break;
    dir = dir.parent_path();
  }
  return {};
}

std::string version() { return ROADBRDF_VERSION; }

}  // namespace roadbrdf
