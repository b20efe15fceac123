// Temporary file, fsync and rename (atomic_file.h), on POSIX calls: the C++
// streams cannot fsync, and without it a power cut after the rename can
// leave an empty file where the old one was.

#include "paintlab/engine/io/atomic_file.h"

#include "paintlab/engine/error.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace paintlab::io {

namespace {

std::string reasonOf(int error_number) { return std::generic_category().message(error_number); }

// Unique per process and call, so two writers of one file never share a temporary.
std::filesystem::path temporaryBeside(const std::filesystem::path& file) {
    static std::atomic<unsigned long> counter{0};
    std::filesystem::path temp = file;
    temp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
    return temp;
}

// The rename is durable only once the folder's entry is on disk; a folder
// that cannot be opened or synced (some network file systems) is not an error.
void syncFolderOf(const std::filesystem::path& file) {
    std::filesystem::path folder = file.parent_path();
    if (folder.empty()) folder = ".";
    const int fd = ::open(folder.c_str(),
                          O_RDONLY | O_DIRECTORY | O_CLOEXEC);  // NOLINT(cppcoreguidelines-pro-type-vararg)
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::filesystem::path file)
    : m_file(std::move(file)), m_temp(temporaryBeside(m_file)) {
    m_fd = ::open(m_temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC,
                  0644);  // NOLINT(cppcoreguidelines-pro-type-vararg)
    if (m_fd < 0)
        throw InputError(m_file.string(), "",
                         "cannot open for writing (temporary file " + m_temp.string() +
                             "): " + reasonOf(errno));
}

AtomicFileWriter::~AtomicFileWriter() {
    if (!m_committed) discard();
}

void AtomicFileWriter::discard() noexcept {
    if (m_fd >= 0) ::close(m_fd);
    m_fd = -1;
    std::error_code ignored;
    std::filesystem::remove(m_temp, ignored);
}

void AtomicFileWriter::write(const void* data, std::size_t size) {
    if (m_fd < 0) throw Error(m_file.string() + ": written after commit or a failure");
    const char* at = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(m_fd, at, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const std::string reason = n < 0 ? reasonOf(errno) : "nothing written";
            discard();
            throw Error(m_file.string() + ": writing failed: " + reason);
        }
        at += n;
        size -= static_cast<std::size_t>(n);
    }
}

void AtomicFileWriter::commit() {
    if (m_fd < 0) throw Error(m_file.string() + ": committed twice or after a failure");
    if (::fsync(m_fd) != 0 || ::close(m_fd) != 0) {
        const std::string reason = reasonOf(errno);
        m_fd = -1;
        discard();
        throw Error(m_file.string() + ": writing failed: " + reason);
    }
    m_fd = -1;
    std::error_code error;
    std::filesystem::rename(m_temp, m_file, error);
    if (error) {
        discard();
        throw Error(m_file.string() + ": cannot replace the file: " + error.message());
    }
    m_committed = true;
    syncFolderOf(m_file);
}

void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes) {
    AtomicFileWriter writer(file);
    writer.write(bytes);
    writer.commit();
}

}  // namespace paintlab::io
