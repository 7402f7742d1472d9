// Messages for the user (warnings, and lines such as "caustic map skipped: no specular surfaces"), written from
// any thread and drained by whoever shows them (Session::take_log → the add-on's Info log and status bar).
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace candela {

class MessageLog {
public:
    void add(std::string message) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_messages.push_back(std::move(message));
    }
    /// The messages added since the last take, oldest first.
    std::vector<std::string> take() {
        std::lock_guard<std::mutex> lock(m_mutex);
        std::vector<std::string> out;
        out.swap(m_messages);
        return out;
    }

private:
    std::mutex m_mutex;
    std::vector<std::string> m_messages;
};

}  // namespace candela
