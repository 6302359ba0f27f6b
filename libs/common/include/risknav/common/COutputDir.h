#pragma once
#include <string>
#include <vector>

namespace risknav::common {
/** An output folder whose files appear all at once, at commit().
 *
 * Each result is written to a hidden temporary name in the same folder
 * (stage()), and commit() renames them to their final names (rename(2) is
 * atomic on one file system). A run that throws before commit() leaves the
 * folder's earlier results untouched: the destructor removes the temporaries.
 */
class COutputDir {
  public:
    /** Creates the folder (and parents). Throws CBadInputError if it cannot
     * (e.g. the path is a file or not writable) or if another run holds it
     * (flock on the folder, held until this object is destroyed: two runs
     * into one folder would mix their files). Removes the temporaries that
     * runs which died before their commit (killed, crashed) left behind. */
    explicit COutputDir(const std::string& dir, const std::string& app = "");
    ~COutputDir();
    COutputDir(const COutputDir&) = delete;
    COutputDir& operator=(const COutputDir&) = delete;

    const std::string& dir() const { return m_dir; }
    /** Final path of a result file (what it will be after commit()). */
    std::string finalPath(const std::string& name) const;
    /** Temporary path to write `name` to; registered for commit(). */
    std::string stage(const std::string& name);
    /** Writes a whole text file to its staged name. */
    void writeText(const std::string& name, const std::string& content);
    /** Renames every staged file to its final name, as one set: the files a
     * previous run committed into the folder (listed in its manifest,
     * kManifest) that this run did not write are removed in the same step, so
     * the folder never holds a mix of two runs (of one app or of two); files
     * the manifest does not list (the user's own) are left alone. Then writes
     * this run's manifest. If any step fails, everything is put back. */
    void commit();
    /** Makes commit() put the files into the subfolder `sub` (emptied first)
     * instead of the folder itself: a partial run's results then never
     * replace a complete earlier run's files. */
    void commitInto(const std::string& sub);
    /** The file listing the last commit's app and files. */
    static constexpr const char* kManifest = ".risknav-run";
    /** Final names staged so far, in order. */
    std::vector<std::string> stagedNames() const;

  private:
    std::string m_dir, m_app;
    std::vector<std::pair<std::string, std::string>> m_staged;  // (temp, final name)
    std::string m_sub;  // commit into this subfolder ("" = the folder itself)
    bool m_committed = false;
    int m_lockFd = -1;
};

/** Writes `content` to `path` through a temporary file + rename. */
void writeFileAtomic(const std::string& path, const std::string& content);

}  // namespace risknav::common
