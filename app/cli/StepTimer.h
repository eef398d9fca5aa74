#pragma once
// Wall-clock timing of solver steps, with the statistics benchmarks report.

#include <algorithm>
#include <chrono>
#include <vector>

namespace wisp::cli {

class StepTimer {
public:
    void start() { m_start = std::chrono::steady_clock::now(); }
    double stop() // milliseconds since start()
    {
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count();
        m_samples.push_back(ms);
        return ms;
    }
    void clear() { m_samples.clear(); }
    std::size_t count() const { return m_samples.size(); }
    double medianMs() const
    {
        if (m_samples.empty())
            return 0.0;
        std::vector<double> s = m_samples;
        std::nth_element(s.begin(), s.begin() + static_cast<long>(s.size() / 2), s.end());
        return s[s.size() / 2];
    }
    double meanMs() const
    {
        double sum = 0.0;
        for (double v : m_samples)
            sum += v;
        return m_samples.empty() ? 0.0 : sum / static_cast<double>(m_samples.size());
    }
    double maxMs() const { return m_samples.empty() ? 0.0 : *std::max_element(m_samples.begin(), m_samples.end()); }

private:
    std::chrono::steady_clock::time_point m_start;
    std::vector<double> m_samples;
};

} // namespace wisp::cli
