#include <risknav/common/CBadInputError.h>
#include <risknav/common/CSpeedLimiter.h>

#include <cmath>
#include <stdexcept>

namespace risknav::common {
IMPLEMENTS_VIRTUAL_MRPT_OBJECT(CSpeedLimiter, mrpt::rtti::CObject, risknav::common)

std::string CSpeedLimiter::knownNames() {
    std::string names;
    for (const auto* id :
         mrpt::rtti::getAllRegisteredClassesChildrenOf(CLASS_ID(CSpeedLimiter))) {
        if (!id->ptrCreateObject)
            continue;  // abstract
        std::string n = id->className;
        const auto colon = n.rfind("::");
        names += (names.empty() ? "" : ", ") +
                 (colon == std::string::npos ? n : n.substr(colon + 2));
    }
    return names.empty() ? "none registered" : names;
}

CSpeedLimiter::Ptr CSpeedLimiter::Factory(const std::string& className) {
    mrpt::rtti::registerAllPendingClasses();
    const auto* id = mrpt::rtti::findRegisteredClass(className, true);
    if (id && id->ptrCreateObject && id->derivedFrom(CLASS_ID(CSpeedLimiter)))
        if (auto p = std::dynamic_pointer_cast<CSpeedLimiter>(
                mrpt::rtti::CObject::Ptr(id->createObject())))
            return p;
    throw CBadInputError("unknown speed limiter '" + className +
                         "' (known: " + knownNames() + ")");
}

TSpeedLimit CSpeedLimiter::limit(const TSpeedLimitInput& in) const {
    if (!in.robot)
        throw std::invalid_argument("CSpeedLimiter::limit: no robot");
    if (!(in.desiredSpeed >= 0) || !std::isfinite(in.desiredSpeed))
        throw std::invalid_argument("CSpeedLimiter::limit: desired speed must be >= 0");
    return impl_limit(in);
}

void CSpeedLimiter::observe(const TSpeedLimitInput& in) const {
    if (!in.robot)
        throw std::invalid_argument("CSpeedLimiter::observe: no robot");
    impl_observe(in);
}

void registerAllClasses_common() {
    mrpt::rtti::registerClass(CLASS_ID(CSpeedLimiter));
}

}  // namespace risknav::common
