// Where the library reports things that are not errors: warnings (a shader that
// compiled with a non-empty log) and progress. Programs install their own sink; the
// default writes to stderr.
#pragma once

#include <functional>
#include <string>

namespace microrelief {

enum class LogLevel { Info, Warning };

using LogSink = std::function<void(LogLevel, const std::string&)>;

void setLogSink(LogSink sink);
void logMessage(LogLevel level, const std::string& message);
inline void logWarning(const std::string& message) {
    logMessage(LogLevel::Warning, message);
}
inline void logInfo(const std::string& message) {
    logMessage(LogLevel::Info, message);
}

}  // namespace microrelief
