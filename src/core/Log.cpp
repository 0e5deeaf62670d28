#include "microrelief/core/Log.h"

#include <iostream>

namespace microrelief {

namespace {
LogSink& sink() {
    static LogSink instance = [](LogLevel level, const std::string& message) {
        std::cerr << "microrelief: " << (level == LogLevel::Warning ? "warning: " : "") << message
                  << '\n';
    };
    return instance;
}
}  // namespace

void setLogSink(LogSink s) {
    sink() = std::move(s);
}

void logMessage(LogLevel level, const std::string& message) {
    if (sink()) sink()(level, message);
}

}  // namespace microrelief
