// Layering probe (tests/CMakeLists.txt): models/ sits below io/, so a models file that includes an
// io header must not compile. The control compiles the same file with io/ on the include path.
#include "roadbrdf/io/geometry_file.h"

int main() { return 0; }
