// Count parsing with k/M/G suffixes and exponents, and range errors that name the limit.
#include "cli/count_option.h"

#include <cmath>
#include <regex>
#include <stdexcept>

namespace weir {

namespace {

// The message for a bad count, without the option's name; empty when `text` is a good count
// (stored in *value).
std::string checkCount(const std::string& text, std::int64_t min, std::int64_t max,
                       const std::string& maxMeaning, std::int64_t* value) {
    static const std::regex form(R"(\s*(\d+(\.\d*)?|\.\d+)([eE][+]?\d+)?\s*([kKmMgGbB]?)\s*)");
    std::smatch match;
    if (!std::regex_match(text, match, form)) {
        return "'" + text + "' is not a count: write e.g. 20000, 20k, 5M or 1e9";
    }
    double number = std::stod(match[1].str() + match[3].str());
    switch (match[4].str().empty() ? ' ' : match[4].str()[0]) {
        case 'k':
        case 'K':
            number *= 1e3;
            break;
        case 'm':
        case 'M':
            number *= 1e6;
            break;
        case 'g':
        case 'G':
        case 'b':
        case 'B':
            number *= 1e9;
            break;
        default:
            break;
    }
    const std::string allowed = "; allowed: " + std::to_string(min) + " to " + std::to_string(max);
    if (number > double(max)) {
        return text + " is more than " + std::to_string(max) +
               (maxMeaning.empty() ? "" : ", " + maxMeaning) + allowed;
    }
    if (number < double(min)) {
        return text + " is less than " + std::to_string(min) + allowed;
    }
    if (number != std::floor(number)) {
        return text + " is not a whole number";
    }
    *value = std::int64_t(number);
    return "";
}

}  // namespace

std::int64_t parseCount(const std::string& text, const std::string& option, std::int64_t min,
                        std::int64_t max, const std::string& maxMeaning) {
    std::int64_t value = 0;
    const std::string error = checkCount(text, min, max, maxMeaning, &value);
    if (!error.empty()) {
        throw std::invalid_argument(option + ": " + error);
    }
    return value;
}

CLI::Validator countOption(std::int64_t min, std::int64_t max, const std::string& maxMeaning) {
    return CLI::Validator(
        [=](std::string& text) {
            std::int64_t value = 0;
            const std::string error = checkCount(text, min, max, maxMeaning, &value);
            if (error.empty()) {
                text = std::to_string(value);
            }
            return error;
        },
        "COUNT");
}

}  // namespace weir
