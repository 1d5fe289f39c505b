#include "roadbrdf/cli/dataset_flags.h"

#include "roadbrdf/cli/request_options.h"

namespace roadbrdf::cli {

void add_dataset_read_flags(CLI::App* command, DatasetReadFlags& flags, bool with_quantity) {
  for (const RequestField<DatasetReadFields>& field : DatasetReadFields::fields()) {
    if (with_quantity || field.name != "quantity") detail::add_field(command, flags, field);
  }
  add_field_table(command, table_flag<DatasetReadFields>);
}

DatasetReadOptions dataset_read_options(const DatasetReadFlags& flags, const std::string& file,
                                        const std::vector<std::string>& files) {
  DatasetReadOptions options;
  run_request<DatasetReadFields>([&] { options = flags.options_for(file, files); });
  return options;
}

std::string with_dataset_flags(const std::string& message) { return with_flags<DatasetReadFields>(message); }

}  // namespace roadbrdf::cli
