// Errors a user can cause: one exception type across the library, carrying the
// category that decides the program's exit status (the spec: 2 for bad arguments or
// bad input, 1 for anything else). Programming errors are assertions, not Errors.
//
// The library knows no command line: a message about a value of a scene desc
// (core/scene/Scene.h) names the field as {field}, the path of the member as the desc spells
// it ("{camera.eye} and {camera.target} must differ"). what() writes each as the field's
// path ("camera.eye and camera.target must differ"); a program writes its own name for
// each, microrelief-render its flags (message(names): "--eye and --target must differ").
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace microrelief {

enum class ErrorKind {
    BadInput,  // a file or argument the user gave is wrong: exit status 2
    Runtime,   // the environment failed us (no GL backend, disk full): exit status 1
};

// `message` with each {field} written as names(field); any other brace (a file name's) is
// kept as it is: a field is one of the scene's (core/scene/Scene.h: isSceneField).
std::string nameFields(const std::string& message,
                       const std::function<std::string(const std::string&)>& names);

class Error : public std::runtime_error {
public:
    // A NUL in the message (from a file's field) is written "\x00": what() is a C string,
    // which would end there. The rest of the escaping is the printer's (core/Text.h).
    Error(ErrorKind kind, const std::string& message)
        : std::runtime_error(nameFields(withoutNul(message), [](const std::string& f) { return f; })),
          kind_(kind),
          message_(withoutNul(message)) {}

    ErrorKind kind() const { return kind_; }
    // The same error, its message after `prefix` (a file and line, a frame), its fields
    // still for the printer to name.
    Error after(const std::string& prefix) const { return Error(kind_, prefix + message_); }
    // The same error, `suffix` after its message (what a program offers instead).
    Error followedBy(const std::string& suffix) const { return Error(kind_, message_ + suffix); }
    // The message with the fields it names written as `names` has them.
    std::string message(const std::function<std::string(const std::string&)>& names) const {
        return nameFields(message_, names);
    }

private:
    static std::string withoutNul(std::string message) {
        for (std::size_t at = message.find('\0'); at != std::string::npos;
             at = message.find('\0', at + 4))
            message.replace(at, 1, "\\x00");
        return message;
    }
    ErrorKind kind_;
    std::string message_;
};

// The exit status the spec gives an error of `kind`: 2 for bad input, 1 otherwise.
inline int exitStatusOf(ErrorKind kind) { return kind == ErrorKind::BadInput ? 2 : 1; }

[[noreturn]] inline void throwBadInput(const std::string& message) {
    throw Error(ErrorKind::BadInput, message);
}

[[noreturn]] inline void throwRuntime(const std::string& message) {
    throw Error(ErrorKind::Runtime, message);
}

}  // namespace microrelief
