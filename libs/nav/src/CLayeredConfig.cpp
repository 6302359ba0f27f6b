#include <risknav/nav/CLayeredConfig.h>

#include <algorithm>
#include <stdexcept>

namespace risknav::nav {
void CLayeredConfig::getAllSections(std::vector<std::string>& sections) const {
    std::vector<std::string> b;
    m_top.getAllSections(sections);
    m_bottom.getAllSections(b);
    for (const auto& s : b)
        if (std::find(sections.begin(), sections.end(), s) == sections.end())
            sections.push_back(s);
}

void CLayeredConfig::getAllKeys(const std::string& section,
                                std::vector<std::string>& keys) const {
    std::vector<std::string> b;
    keys.clear();
    if (m_top.sectionExists(section))
        m_top.getAllKeys(section, keys);
    if (m_bottom.sectionExists(section))
        m_bottom.getAllKeys(section, b);
    for (const auto& k : b)
        if (std::find(keys.begin(), keys.end(), k) == keys.end())
            keys.push_back(k);
}

void CLayeredConfig::clear() {
    throw std::logic_error("CLayeredConfig is read-only");
}

void CLayeredConfig::writeString(const std::string&, const std::string&,
                                 const std::string&) {
    throw std::logic_error("CLayeredConfig is read-only");
}

std::string CLayeredConfig::readString(const std::string& section,
                                       const std::string& name, const std::string& def,
                                       bool failIfNotFound) const {
    if (m_top.keyExists(section, name))
        return m_top.read_string(section, name, def, failIfNotFound);
    return m_bottom.read_string(section, name, def, failIfNotFound);
}

}  // namespace risknav::nav
