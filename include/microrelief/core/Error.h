// Errors a user can cause: one exception type across the library, carrying the
// category that decides the program's exit status (the spec: 2 for bad arguments or
// bad input, 1 for anything else). Programming errors are assertions, not Errors.
#pragma once

#include <stdexcept>
#include <string>

namespace microrelief {

enum class ErrorKind {
    BadInput,  // a file or argument the user gave is wrong: exit status 2
    Runtime,   // the environment failed us (no GL backend, disk full): exit status 1
};

class Error : public std::runtime_error {
public:
    // A NUL in the message (from a file's field) is written "\x00": what() is a C string,
    // which would end there. The rest of the escaping is the printer's (core/Text.h).
    Error(ErrorKind kind, const std::string& message)
        : std::runtime_error(withoutNul(message)), kind_(kind) {}

    ErrorKind kind() const { return kind_; }
    int exitStatus() const { return kind_ == ErrorKind::BadInput ? 2 : 1; }

private:
    static std::string withoutNul(std::string message) {
        for (std::size_t at = message.find('\0'); at != std::string::npos;
             at = message.find('\0', at + 4))
            message.replace(at, 1, "\\x00");
        return message;
    }
    ErrorKind kind_;
};

[[noreturn]] inline void throwBadInput(const std::string& message) {
    throw Error(ErrorKind::BadInput, message);
}

[[noreturn]] inline void throwRuntime(const std::string& message) {
    throw Error(ErrorKind::Runtime, message);
}

}  // namespace microrelief
