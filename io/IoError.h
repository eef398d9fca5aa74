#pragma once
// io/ reports failures as values: what file, where in it, and what was wrong. Only app/ shows them.

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace wisp::io {

struct IoError {
    std::string file; // the path as the user gave it
    std::string location; // "line 12", "byte 1024", "regions[1].clump_degree"; empty when not applicable
    std::string message; // what was wrong, in words an artist can act on

    // "head.obj: line 12: a face refers to vertex 90 of 80"
    std::string toString() const
    {
        std::string s = file;
        if (!location.empty())
            s += ": " + location;
        return s + ": " + message;
    }
};

template <typename T> class Result {
public:
    Result(T value)
        : m_value(std::move(value))
    {
    }
    Result(IoError error)
        : m_value(std::move(error))
    {
    }

    bool ok() const { return std::holds_alternative<T>(m_value); }
    explicit operator bool() const { return ok(); }
    const T& value() const& { return std::get<T>(m_value); }
    T&& value() && { return std::get<T>(std::move(m_value)); }
    const IoError& error() const { return std::get<IoError>(m_value); }

private:
    std::variant<T, IoError> m_value;
};

// What every io/ writer returns: nothing on success, or the IoError. [[nodiscard]]: a write whose
// failure is dropped loses the artist's work without a word.
template <> class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(IoError error)
        : m_error(std::move(error))
    {
    }

    bool ok() const { return !m_error.has_value(); }
    explicit operator bool() const { return ok(); }
    const IoError& error() const { return *m_error; }

private:
    std::optional<IoError> m_error;
};

} // namespace wisp::io
