#include "util/error.h"

namespace attend::internal {

CheckFailure::CheckFailure(const char* file, int line, const char* condition) {
  stream_ << "internal check failed at " << file << ":" << line << ": " << condition << " ";
}

CheckFailure::~CheckFailure() noexcept(false) { throw InternalError(stream_.str()); }

}  // namespace attend::internal
