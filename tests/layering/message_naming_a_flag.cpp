// Probe of layering.library_messages_name_fields (tests/CMakeLists.txt): the checker must report the
// literal of refuse() and nothing else (a flag in a comment, --like-this, is no message).
#include <stdexcept>

void refuse() { throw std::runtime_error("pass --delimiter ';'"); /* nor "--in-a-block-comment" */ }

int main() { return '"' == 0 ? 1 : 0; }
