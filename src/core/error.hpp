// The one exception type core code throws. Its kind decides the SQLSTATE at the boundary
// (src/pg/boundary.cpp holds the table), so core never needs to know about SQLSTATEs.
#pragma once
#include "core/no_postgres.hpp"

#include <stdexcept>
#include <string>

namespace streetgen::core {

enum class ErrorKind {
  invalid_argument,  // a parameter value a caller can fix (22023)
  null_argument,     // a required parameter is NULL (22004)
  bad_data,          // input data that cannot be parsed or is inconsistent (22000)
  geometry_engine,   // GEOS or CGAL failed on valid-looking input (38000)
  out_of_memory,     // (53200)
  canceled,          // an interrupt was seen while polling; the boundary re-raises PostgreSQL's own
  internal,          // a bug (XX000)
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message, std::string detail = {}, std::string hint = {})
      : std::runtime_error(message), kind_(kind), detail_(std::move(detail)), hint_(std::move(hint)) {}

  ErrorKind kind() const noexcept { return kind_; }
  const std::string& detail() const noexcept { return detail_; }
  const std::string& hint() const noexcept { return hint_; }

 private:
  ErrorKind kind_;
  std::string detail_;
  std::string hint_;
};

[[noreturn]] inline void throw_invalid_argument(const std::string& message, std::string detail = {},
                                                std::string hint = {}) {
  throw Error(ErrorKind::invalid_argument, message, std::move(detail), std::move(hint));
}

}  // namespace streetgen::core
