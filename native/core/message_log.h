// Messages for the user, written from any thread and drained by whoever shows them (Session::take_log_entries →
// the add-on's Info log; the CLI's stderr). Each has a level: a warning says the image may not be what the user
// expects (a setting ignored, a black world, dropped samples); an info line says what the renderer did ("caustic
// map skipped: no specular surfaces", AUTO's choice), shown as Blender's Info reports and left out of the status
// line and of `candela -q`.
#pragma once

#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace candela {

enum class LogLevel : unsigned char { Info, Warning };

inline const char* log_level_name(LogLevel level) { return level == LogLevel::Info ? "INFO" : "WARNING"; }

struct LogEntry {
    LogLevel level = LogLevel::Warning;
    std::string message;
};

class MessageLog {
public:
    /// A warning.
    void add(std::string message) { add(LogLevel::Warning, std::move(message)); }
    void add(LogLevel level, std::string message) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_entries.push_back({level, std::move(message)});
    }
    /// The entries added since the last take, oldest first.
    std::vector<LogEntry> take_entries() {
        std::lock_guard<std::mutex> lock(m_mutex);
        std::vector<LogEntry> out;
        out.swap(m_entries);
        return out;
    }
    /// The same, messages only.
    std::vector<std::string> take() {
        std::vector<std::string> out;
        for (auto& e : take_entries()) out.push_back(std::move(e.message));
        return out;
    }

private:
    std::mutex m_mutex;
    std::vector<LogEntry> m_entries;
};

}  // namespace candela
