// CGATS through liblcms2 (io/cgats.h). lcms2's error messages, with the
// line, arrive through the context's log handler and are rethrown as
// InputError naming the file.

#include "paintlab/engine/io/cgats.h"

#include "paintlab/engine/error.h"

#include <lcms2.h>

#include <cctype>
#include <charconv>
#include <memory>
#include <type_traits>

namespace paintlab::io {

namespace {

// The messages lcms2 logs while parsing, for the exception.
struct Log {
    std::string messages;
};

// lcms2 writes "<file name>: Line 9, <message>\n"; the file name is empty
// when parsing from memory, and the caller names the file.
void logHandler(cmsContext context, cmsUInt32Number /*code*/, const char* text) {
    auto* log = static_cast<Log*>(cmsGetContextUserData(context));
    if (log == nullptr || text == nullptr) return;
    std::string_view message = text;
    if (message.starts_with(": ")) message.remove_prefix(2);
    if (!log->messages.empty()) log->messages.append("; ");
    if (message.starts_with("Line ")) {
        log->messages.append("line ");
        message.remove_prefix(5);
    }
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back())) != 0)
        message.remove_suffix(1);
    log->messages.append(message);
}

struct ContextDeleter {
    void operator()(cmsContext context) const { cmsDeleteContext(context); }
};
struct It8Deleter {
    void operator()(void* handle) const { cmsIT8Free(handle); }
};

// A NUMBER_OF_SETS or NUMBER_OF_FIELDS that the text cannot hold (every
// value takes a character and a separator) is refused before lcms2 reads it,
// with the keyword named: lcms2 would report a mismatch on some later line.
void checkCounts(std::string_view text, const std::string& source) {
    for (const std::string_view key : {"NUMBER_OF_SETS", "NUMBER_OF_FIELDS"}) {
        std::size_t at = text.find(key);
        while (at != std::string_view::npos && at > 0 && text[at - 1] != '\n' && text[at - 1] != '\r')
            at = text.find(key, at + 1);
        if (at == std::string_view::npos) continue;
        std::string_view rest = text.substr(at + key.size());
        while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
        const std::string_view token = rest.substr(0, rest.find_first_of(" \t\r\n"));
        double value = 0.0;
        const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (error == std::errc() && end == token.data() + token.size() &&
            value > static_cast<double>(text.size()) / 2.0)
            throw InputError(source, std::string(key),
                             "'" + std::string(token) + "' is more than a file of " +
                                 std::to_string(text.size()) + " bytes can hold");
    }
}

}  // namespace

std::string CgatsTable::property(std::string_view key) const {
    const auto found = properties.find(key);
    return found == properties.end() ? std::string() : found->second;
}

std::size_t CgatsTable::valueCount() const {
    std::size_t count = 0;
    for (const auto& row : rows)
        for (const auto& cell : row) count += cell.empty() ? 0U : 1U;
    return count;
}

CgatsTable parseCgats(std::string_view text, const std::string& source) {
    Log log;
    const std::unique_ptr<std::remove_pointer_t<cmsContext>, ContextDeleter> context(
        cmsCreateContext(nullptr, &log));
    if (!context) throw Error("liblcms2: cannot create a context");
    cmsSetLogErrorHandlerTHR(context.get(), logHandler);
    if (text.size() > 0xffffffffU) throw InputError(source, "", "too large for a CGATS file");
    checkCounts(text, source);
    const std::unique_ptr<void, It8Deleter> it8(
        cmsIT8LoadFromMem(context.get(), text.data(), static_cast<cmsUInt32Number>(text.size())));
    if (!it8)
        throw InputError(source, "",
                         "not a readable CGATS/IT8 file: " +
                             (log.messages.empty() ? std::string("no CGATS structure") : log.messages));
    if (cmsIT8TableCount(it8.get()) != 1)
        throw InputError(source, "",
                         "has " + std::to_string(cmsIT8TableCount(it8.get())) +
                             " tables; one table is expected");

    CgatsTable table;
    char** names = nullptr;
    const int properties = static_cast<int>(cmsIT8EnumProperties(it8.get(), &names));
    for (int p = 0; p < properties; ++p) {
        if (names[p] == nullptr) continue;
        const char* value = cmsIT8GetProperty(it8.get(), names[p]);
        table.properties[names[p]] = value != nullptr ? value : "";
    }
    const int columns = cmsIT8EnumDataFormat(it8.get(), &names);
    for (int c = 0; c < columns; ++c) table.columns.emplace_back(names[c] != nullptr ? names[c] : "");
    const double sets = cmsIT8GetPropertyDbl(it8.get(), "NUMBER_OF_SETS");
    const int rows = sets >= 1.0 && sets < 1e9 ? static_cast<int>(sets) : 0;
    table.rows.resize(static_cast<std::size_t>(rows));
    for (int row = 0; row < rows; ++row) {
        auto& cells = table.rows[static_cast<std::size_t>(row)];
        cells.reserve(table.columns.size());
        for (int c = 0; c < columns; ++c) {
            const char* value = cmsIT8GetDataRowCol(it8.get(), row, c);
            cells.emplace_back(value != nullptr ? value : "");
        }
    }
    return table;
}

}  // namespace paintlab::io
