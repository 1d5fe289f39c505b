// libFuzzer entry point of the dataset reader with a column mapping, fixed angles and a quantity
// (io/dataset_runs.h): the input's first line holds the items of the per-file grammar, separated by
// spaces (an item starting with '@' is a `set` item, any other a `columns` item); the rest is the table,
// read as brf and as brdf-cos, alone and combined with itself as two runs.
#pragma once

#include <string>
#include <vector>

#include "fuzz/parser_harnesses.h"
#include "roadbrdf/io/dataset_runs.h"

namespace roadbrdf::fuzz {

inline int dataset_mapped_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = bytes(data, size);
  const std::size_t end = text.find('\n');
  const std::string_view items = text.substr(0, end);
  const ScratchFile file("mapped.csv", end == std::string_view::npos ? std::string_view() : text.substr(end + 1));
  DatasetReadFields fields;
  std::size_t at = 0;
  while (at < items.size()) {
    std::size_t next = items.find(' ', at);
    if (next == std::string_view::npos) next = items.size();
    const std::string_view item = items.substr(at, next - at);
    if (!item.empty()) {
      if (item.front() == '@') {
        fields.set.emplace_back(item.substr(1));
      } else {
        fields.columns.emplace_back(item);
      }
    }
    at = next + 1;
  }
  for (const char* quantity : {"brf", "brdf-cos"}) {
    fields.quantity = quantity;
    fields.average_duplicates = fields.quantity == "brf";
    refusing([&] { read_dataset_runs({file.path()}, fields, quiet); });
    refusing([&] { read_dataset_runs({file.path(), file.path()}, fields, quiet); });
  }
  return 0;
}

}  // namespace roadbrdf::fuzz
