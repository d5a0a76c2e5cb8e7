// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/configuration/argos_exception.h>.
// The macro has ARGoS's meaning (throw a CARGoSException built from a stream expression).
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_EXCEPTION_H
#define ARGOS_EXCEPTION_H

#include <exception>
#include <sstream>
#include <string>

namespace argos {
class CARGoSException : public std::exception {
public:
    CARGoSException(const std::string& str_what, std::exception* pc_nested = nullptr);
    ~CARGoSException() noexcept override;
    const char* what() const noexcept override;
};
}  // namespace argos

#define THROW_ARGOSEXCEPTION(message)                      \
    {                                                      \
        std::ostringstream w_msg;                          \
        w_msg << message;                                  \
        throw argos::CARGoSException(w_msg.str());         \
    }

#endif
