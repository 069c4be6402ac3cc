// TESSERA_CHECK: a broken contract inside the program (a caller's bug) aborts with file and line.
// Bad input from outside never goes through here: it is a returned Expected<T> with a message.
#pragma once

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace tessera::detail {

class CheckFailure {
 public:
  CheckFailure(const char* file, int line, const char* condition) {
    stream_ << file << ":" << line << ": check failed: " << condition << ": ";
  }
  [[noreturn]] ~CheckFailure() {
    std::cerr << stream_.str() << std::endl;
    std::abort();
  }
  template <typename T>
  CheckFailure& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }

 private:
  std::ostringstream stream_;
};

}  // namespace tessera::detail

#define TESSERA_CHECK(cond) \
  if (cond) {               \
  } else                    \
    ::tessera::detail::CheckFailure(__FILE__, __LINE__, #cond)
