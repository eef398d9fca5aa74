#pragma once
// A growth region's painted weights (one 0..1 value per head vertex), shared copy-on-write.
//
// Copying a region (every undo command that snapshots the region list, every groom handed to the
// simulation thread) shares the weights instead of copying one float per vertex; the first write
// through forWrite() on shared weights copies them, so snapshots never change (Blender's
// ImplicitSharingInfo habit). Reading is through a read-only view; nobody can change weights that
// another holder sees.
//
// Thread: the buffer is immutable while shared, so holders may read it on any thread. forWrite()
// belongs to the one thread that owns this holder (the GUI's document).

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace wisp {

class RegionWeights {
public:
    using value_type = float;
    using iterator = const float*;
    using const_iterator = const float*;

    RegionWeights() = default;
    RegionWeights(std::vector<float> values) // NOLINT: implicit, a vector of weights is weights
        : m_values(values.empty() ? nullptr : std::make_shared<std::vector<float>>(std::move(values)))
    {
    }
    RegionWeights(std::initializer_list<float> values)
        : RegionWeights(std::vector<float>(values))
    {
    }

    std::size_t size() const { return m_values ? m_values->size() : 0; }
    bool empty() const { return size() == 0; }
    const float* data() const { return m_values ? m_values->data() : nullptr; }
    float operator[](std::size_t i) const { return (*m_values)[i]; }
    const float* begin() const { return data(); }
    const float* end() const { return data() + size(); }
    std::span<const float> span() const { return { data(), size() }; }
    operator std::span<const float>() const { return span(); } // NOLINT: reads as a span anywhere
    // A copy as a plain vector (for holders that keep their own, e.g. the viewport's overlay).
    std::vector<float> toVector() const { return { begin(), end() }; }

    // The weights to change in place: copies them first when another holder shares them, so the
    // reference is this holder's alone until it is copied again (do not copy the holder while
    // writing through the reference).
    std::vector<float>& forWrite()
    {
        if (!m_values)
            m_values = std::make_shared<std::vector<float>>();
        else if (m_values.use_count() > 1)
            m_values = std::make_shared<std::vector<float>>(*m_values);
        return *m_values;
    }
    void assign(std::size_t count, float value) { *this = RegionWeights(std::vector<float>(count, value)); }

    // Whether both holders read the very same buffer (no copy was made between them).
    bool sharesBufferWith(const RegionWeights& other) const { return m_values && m_values == other.m_values; }
    // How many holders share this buffer (0 for no weights); for tests and memory figures.
    long holderCount() const { return m_values.use_count(); }

    friend bool operator==(const RegionWeights& a, const RegionWeights& b)
    {
        return a.m_values == b.m_values || std::equal(a.begin(), a.end(), b.begin(), b.end());
    }

private:
    // Never handed out as non-const while shared (use_count > 1).
    std::shared_ptr<std::vector<float>> m_values;
};

} // namespace wisp
