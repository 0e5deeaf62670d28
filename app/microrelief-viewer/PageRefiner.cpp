#include "PageRefiner.h"

#include <algorithm>

namespace microrelief {

bool PageRefiner::afterDraw(bool anotherView, const std::vector<int>& wanted, const Load& load) {
    if (anotherView) {  // what the last view kept may go
        kept_.clear();
        poolTooSmall_ = false;
    }
    wanted_ = wanted.size();
    if (wanted.empty() || poolTooSmall_) return false;
    // Each load keeps what the view's draws loaded before, so the view either ends wanting
    // nothing or runs out of pool (a load of nothing): it never loads the same page twice.
    const std::vector<int> some(
        wanted.begin(),
        wanted.begin() + static_cast<std::ptrdiff_t>(std::min(wanted.size(), kPagesPerFrame)));
    const std::size_t loaded = std::min(load(some, kept_), some.size());
    if (loaded == 0) {  // the pool holds what the view keeps and nothing more
        poolTooSmall_ = true;
        return true;
    }
    kept_.insert(kept_.end(), some.begin(), some.begin() + static_cast<std::ptrdiff_t>(loaded));
    ++generation_;  // the view is drawn again with them
    return false;
}

void PageRefiner::noPages() {
    wanted_ = 0;
    poolTooSmall_ = false;
}

std::string PageRefiner::progress() const {
    return !pagesWanted()  ? "exact"
           : poolTooSmall_ ? "coarse in parts, raise --memory"
                           : "refining, " + std::to_string(wanted_) + " wanted";
}

}  // namespace microrelief
