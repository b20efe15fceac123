#pragma once
// The small exception hierarchy of PaintLab (after F3D's library/public/exception.h).
// - InputError: the user gave something wrong (a file, a field, a value). The
//   message names the file and the field; the CLI maps it to exit code 2.
// - Error: anything else that went wrong; the CLI maps it to exit code 1.
// Hot numeric code never throws (see STYLE.md); these are for I/O and validation.

#include <stdexcept>
#include <string>

namespace paintlab {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class InputError : public Error {
public:
    // source: the file (or "<stdin>", "<argument>") the bad input came from; may be empty.
    // field: a path to the offending field, e.g. "layers[1] 'basecoat'.components[0].volume_fraction".
    InputError(std::string source, std::string field, const std::string& message)
        : Error(compose(source, field, message)), m_source(std::move(source)), m_field(std::move(field)),
          m_detail(message) {}

    const std::string& source() const noexcept { return m_source; }
    const std::string& field() const noexcept { return m_field; }
    const std::string& detail() const noexcept { return m_detail; }

private:
    static std::string compose(const std::string& source, const std::string& field,
                               const std::string& message) {
        std::string text;
        if (!source.empty()) text += source + ": ";
        if (!field.empty()) text += field + ": ";
        return text + message;
    }

    std::string m_source;
    std::string m_field;
    std::string m_detail;
};

}  // namespace paintlab
