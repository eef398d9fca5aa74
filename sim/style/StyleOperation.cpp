#include "sim/style/StyleOperation.h"

#include "sim/style/BlowDryOperation.h"
#include "sim/style/CombOperation.h"
#include "sim/style/CutOperation.h"
#include "sim/style/LengthOperation.h"
#include "sim/style/WispDabOperation.h"

namespace wisp {

std::unique_ptr<StyleOperation> makeStyleOperation(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb:
        return std::make_unique<CombOperation>();
    case StyleBrush::Cut:
        return std::make_unique<CutOperation>();
    case StyleBrush::Length:
        return std::make_unique<LengthOperation>();
    case StyleBrush::Curl:
        return std::make_unique<CurlOperation>();
    case StyleBrush::Wet:
        return std::make_unique<WetOperation>();
    case StyleBrush::Hairspray:
        return std::make_unique<HairsprayOperation>();
    case StyleBrush::BlowDry:
        return std::make_unique<BlowDryOperation>();
    }
    return nullptr;
}

} // namespace wisp
