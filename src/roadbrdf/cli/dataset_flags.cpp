#include "roadbrdf/cli/dataset_flags.h"

#include "roadbrdf/io/dataset_dialect.h"

namespace roadbrdf::cli {

void add_dataset_read_flags(CLI::App* command, DatasetReadFlags& flags) {
  command->add_option("--delimiter", flags.delimiter,
                      "Dataset cell delimiter: auto (default: from the header line), ',', ';' or tab");
  command->add_option("--decimal", flags.decimal,
                      "Dataset decimal separator: auto (default: from the numbers), '.' or ',' (with ';' or tab)");
  command->add_flag("--average-duplicates", flags.average_duplicates,
                    "Average dataset rows with the same geometry (else an error)");
}

DatasetReadOptions dataset_read_options(const DatasetReadFlags& flags) {
  DatasetReadOptions o;
  o.delimiter = delimiter_from_name(flags.delimiter);
  o.decimal = decimal_from_name(flags.decimal);
  o.average_duplicates = flags.average_duplicates;
  validate_read_options(o);
  return o;
}

}  // namespace roadbrdf::cli
