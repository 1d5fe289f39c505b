// Location of the bundled data tables (data/ in the source tree).
#pragma once

#include <string>

namespace roadbrdf {

// Directory of the bundled data: $ROADBRDF_DATA if set, else the source tree's data/ folder.
std::string data_directory();
// data_directory() + "/" + relative; throws InputError if the file does not exist.
std::string data_file(const std::string& relative);

}  // namespace roadbrdf
