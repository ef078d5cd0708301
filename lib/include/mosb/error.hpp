#pragma once

#include <stdexcept>
#include <string>

namespace mosb {

// Every failure mosb reports to a user: the message is one line and names the file it concerns.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mosb
