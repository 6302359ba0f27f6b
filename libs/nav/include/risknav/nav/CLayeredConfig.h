#pragma once
#include <risknav/common/config_read.h>

#include <mrpt/config/CConfigFileBase.h>

namespace risknav::nav {
/** Two configs seen as one, for MRPT's engine: a key in `top` (the run's
 * config) wins over the same key in `bottom` (e.g. the user's MRPT
 * reactive-navigation file named by [Navigate] engine_config). Reads go to
 * the config that holds the key, so each keeps its own read tracking and
 * error messages. Read-only: writes throw. */
class CLayeredConfig : public mrpt::config::CConfigFileBase,
                       public common::CConfigOrigins {
  public:
    CLayeredConfig(const mrpt::config::CConfigFileBase& top,
                   const mrpt::config::CConfigFileBase& bottom)
        : m_top(top), m_bottom(bottom) {}
    void getAllSections(std::vector<std::string>& sections) const override;
    void getAllKeys(const std::string& section,
                    std::vector<std::string>& keys) const override;
    void clear() override;
    /** `top` when it holds the key, else `bottom`. */
    const mrpt::config::CConfigFileBase& holderOf(const std::string& section,
                                                  const std::string& key) const override {
        return m_top.keyExists(section, key) ? m_top : m_bottom;
    }

  protected:
    void writeString(const std::string& section, const std::string& name,
                     const std::string& str) override;
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& defaultStr,
                           bool failIfNotFound = false) const override;

  private:
    const mrpt::config::CConfigFileBase& m_top;
    const mrpt::config::CConfigFileBase& m_bottom;
};

}  // namespace risknav::nav
