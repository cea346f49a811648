#include "util/error.h"

namespace attend {

namespace {

// `at` moved back to the first byte of a UTF-8 character.
size_t CharacterStart(const std::string& text, size_t at) {
  while (at > 0 && at < text.size() && (static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) --at;
  return at;
}

}  // namespace

std::string Error::BoundedMessage(const std::string& message) {
  if (message.size() <= kMaxMessageBytes) return message;
  const size_t head = CharacterStart(message, kMaxMessageBytes * 3 / 4);
  const size_t tail = CharacterStart(message, message.size() - kMaxMessageBytes / 8);
  return message.substr(0, head) + " [... " + std::to_string(tail - head) + " bytes left out ...] " +
         message.substr(tail);
}

}  // namespace attend

namespace attend::internal {

CheckFailure::CheckFailure(const char* file, int line, const char* condition) {
  stream_ << "internal check failed at " << file << ":" << line << ": " << condition << " ";
}

CheckFailure::~CheckFailure() noexcept(false) { throw InternalError(stream_.str()); }

}  // namespace attend::internal
