#pragma once
// The registry's tables are indexed by their enum (parameterInfo(Param), motionSettingInfo): each
// row must sit at its id's index, which the tables check at compile time with this.

#include <cstddef>

namespace wisp {

// True when every row's `id`, as an index, is the row's own index.
template <class Table> constexpr bool rowsAreInEnumOrder(const Table& table)
{
    for (std::size_t i = 0; i < table.size(); ++i)
        if (static_cast<std::size_t>(table[i].id) != i)
            return false;
    return true;
}

} // namespace wisp
