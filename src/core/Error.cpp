#include "microrelief/core/Error.h"

#include "microrelief/core/scene/SceneFields.h"

#include <algorithm>
#include <cctype>
namespace microrelief {

std::string nameFields(const std::string& message,
                       const std::function<std::string(const std::string&)>& names) {
    std::string out;
    std::size_t at = 0;
    while (at < message.size()) {
        const std::size_t open = message.find('{', at);
        if (open == std::string::npos) break;
        std::size_t close = open + 1;
        while (close < message.size() &&
               (std::isalnum(static_cast<unsigned char>(message[close])) || message[close] == '.' ||
                message[close] == '_'))
            ++close;
        out.append(message, at, open - at);
        if (close < message.size() && message[close] == '}' &&
            isSceneField(message.substr(open + 1, close - open - 1))) {
            out += names(message.substr(open + 1, close - open - 1));
            at = close + 1;
        } else {
            out += '{';
            at = open + 1;
        }
    }
    out.append(message, std::min(at, message.size()), std::string::npos);
    return out;
}

}  // namespace microrelief
