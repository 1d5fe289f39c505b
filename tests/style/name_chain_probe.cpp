// Control of style.names_come_from_tables: the checker must report the comparison on line 7.
#include <string_view>

enum class Shade { kLight, kDark };

inline Shade shade_of(std::string_view text) {
  if (text == "dark") return Shade::kDark;
  return Shade::kLight;
}
