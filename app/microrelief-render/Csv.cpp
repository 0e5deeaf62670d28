#include "Csv.h"

namespace microrelief {

namespace {

std::string trimmed(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

}  // namespace

std::optional<std::vector<std::string>> splitCsvLine(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t k = 0;
    while (true) {
        std::string field;
        const std::size_t start = line.find_first_not_of(" \t", k);
        if (start != std::string::npos && line[start] == '"') {
            std::size_t p = start + 1;
            while (true) {
                if (p >= line.size()) return std::nullopt;  // the quote is not closed
                if (line[p] == '"') {
                    if (p + 1 < line.size() && line[p + 1] == '"') {
                        field += '"';
                        p += 2;
                        continue;
                    }
                    break;
                }
                field += line[p++];
            }
            const std::size_t next = line.find_first_not_of(" \t", p + 1);
            if (next != std::string::npos && line[next] != ',') return std::nullopt;
            fields.push_back(field);
            if (next == std::string::npos) return fields;
            k = next + 1;
        } else {
            const std::size_t comma = line.find(',', k);
            field = trimmed(line.substr(k, comma == std::string::npos ? comma : comma - k));
            if (field.find('"') != std::string::npos) return std::nullopt;
            fields.push_back(field);
            if (comma == std::string::npos) return fields;
            k = comma + 1;
        }
    }
}

std::string csvField(const std::string& field) {
    const bool plain = field.find_first_of(",\"\r\n") == std::string::npos &&
                       (field.empty() || (field.front() != ' ' && field.back() != ' '));
    if (plain) return field;
    std::string quoted = "\"";
    for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace microrelief
