// Probe of layering.library_messages_name_fields (tests/CMakeLists.txt): the checker must report the
// literal of refuse() and nothing else (a flag in a comment, --like-this, is no message; nor is the
// flag a request's field-table row declares).
#include <stdexcept>

void refuse() { throw std::runtime_error("pass --delimiter ';'"); /* nor "--in-a-block-comment" */ }

struct Row {
  const char* name;
  const char* flag;
};
const Row kFields[] = {{"field_name", "--table-row-flag"}};

int main() { return '"' == 0 ? 1 : kFields[0].name[0] == 0; }
