// Where roadbrdf finds its bundled data tables and, for `roadbrdf plot`, its Python package.
//
// No path is compiled in. Everything is found relative to the file that holds this code (the
// program, a test program, or the Python extension), by looking in each of its ancestor folders
// for share/roadbrdf/data; the build tree has the same layout as an installed tree:
//   build tree  build/roadbrdf, build/tests/*, build/python/roadbrdf/_roadbrdf*.so  ->  build/share/roadbrdf/data
//   installed   P/bin/roadbrdf, P/lib/python3/dist-packages/roadbrdf/_roadbrdf*.so  ->  P/share/roadbrdf/data
//   pip         .../site-packages/roadbrdf/_roadbrdf*.so                           ->  sys.prefix/share/roadbrdf/data
// $ROADBRDF_DATA overrides the data folder.
#pragma once

#include <filesystem>
#include <string>

namespace roadbrdf {

// Directory of the bundled data (data/ of the source tree). Throws InputError when not found.
std::string data_directory();
// data_directory() + "/" + relative; throws InputError if the file does not exist.
std::string data_file(const std::string& relative);

// Folder of the file this code was loaded from (the executable, or the shared object).
std::filesystem::path image_directory();

// The folder holding the `roadbrdf` Python package that belongs to this program: build/python in
// the build tree, P/<python dir> when installed. Empty when there is none (e.g. installed by pip,
// where the package is on the interpreter's own path).
std::string python_package_parent();

// The roadbrdf version ("0.1.0").
std::string version();

}  // namespace roadbrdf
