#pragma once
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace risknav::common {
/** An output folder whose results appear all at once, at commit(), and which
 * never loses or touches a file that is not a risknav run's.
 *
 * The rules (each a test in tests/unit/common/test_output*.cpp):
 * - Results are written into a staging folder of the run's own inside the
 *   output folder (`.risknav-stage-XXXXXX`, made by mkdtemp: a fresh name only
 *   this run can write in, holding an owner marker), so no temporary name can
 *   be planted beforehand (a symlink at it) and no writer follows one.
 * - commit() replaces only what the last run into the folder wrote, as its
 *   manifest (kManifest) lists it, and never an input of this run (a file
 *   this process read: see noteRunInput()). Any other file or folder in the
 *   way of an output, or a symlink there, is refused with CBadInputError
 *   (exit 2) before the work for the names given to the constructor, and at
 *   stage() for the others.
 * - The commit is all-or-nothing across a kill at any instant: its renames
 *   are listed first in a journal (written and synced before the first
 *   rename); a run killed before the journal leaves the earlier set whole,
 *   one killed after it leaves a journal that the next run into the folder
 *   completes. A commit that fails (a rename refused) puts everything back.
 * - The next run removes a killed run's staging folder, recognized by its
 *   owner marker, not by its name alone; nothing else is ever removed but the
 *   files and folders the manifest lists.
 * One run per folder at a time (a lock on the folder). */
class COutputDir {
  public:
    /** Creates the folder (and parents). Throws CBadInputError if it cannot
     * (the path is a file or a symlink, a name is longer than the file system
     * takes, not writable), if another run holds it, or if one of `outputs`
     * (final names this run will write; summary.json and
     * config_effective.ini always) cannot be replaced. Completes or removes
     * what a killed run left. */
    explicit COutputDir(const std::string& dir, const std::string& app = "",
                        const std::vector<std::string>& outputs = {});
    ~COutputDir();
    COutputDir(const COutputDir&) = delete;
    COutputDir& operator=(const COutputDir&) = delete;

    const std::string& dir() const { return m_dir; }
    /** Final path of a result (what it will be after commit()). */
    std::string finalPath(const std::string& name) const;
    /** Path to write the result `name` to ("a.png", or "snapshots/b.png" for a
     * file in a subfolder that the run writes whole): a new, empty regular
     * file created exclusively in the staging folder; registered for commit().
     * Throws CBadInputError if the final name cannot be replaced. */
    std::string stage(const std::string& name);
    /** A folder for the run's own scratch files, removed with the staging
     * folder (also after a kill, by the next run). */
    std::string scratchDir(const std::string& name);
    /** Writes a whole text file to its staged name. */
    void writeText(const std::string& name, const std::string& content);
    /** Puts every staged result in place as one set, replacing the last run's
     * set (its manifest's files that this run did not write are removed in the
     * same step), and writes this run's manifest. Throws std::runtime_error if
     * a step fails, after putting everything back. */
    void commit();
    /** Makes commit() put the results into the subfolder `sub` (replaced
     * whole) instead of the folder itself, keeping the last run's set: a
     * partial run's results then never replace a complete run's files. */
    void commitInto(const std::string& sub);
    /** The file listing the last commit's app, files and folders. */
    static constexpr const char* kManifest = ".risknav-run";
    /** Final names staged so far, in order. */
    std::vector<std::string> stagedNames() const;

    /** For tests of the commit's atomicity: called with 1, 2, ... before each
     * step of commit() that changes the file system (a kill there must leave
     * the folder recoverable). Empty by default. */
    static void setCommitStepHook(std::function<void(int)> hook);

  private:
    std::string m_dir, m_app, m_stage;
    std::vector<std::pair<std::string, std::string>> m_staged;  // (staged path, name)
    std::string m_sub;  // commit into this subfolder ("" = the folder itself)
    int m_lockFd = -1;

    void checkReplaceable(const std::string& top) const;
};

/** Notes `path` as an input of this run: no COutputDir of this process
 * replaces it (compared by device and inode, so also through another name, a
 * symlink or a hard link). File readers call it through fileProblem(). */
void noteRunInput(const std::string& path);
/** True if `path` (followed if a symlink) is a file noted by noteRunInput(). */
bool isRunInput(const std::string& path);

/** The path a user sees for a file being written: a staged path is shown as
 * its final path (the staging folder is the run's own business). */
std::string shownOutputPath(const std::string& path);
/** "cannot write <shown path>: <the system's reason for errnum>", for exit 1. */
std::runtime_error writeFailure(const std::string& path, int errnum);

/** Writes `content` as the whole of `path` (created, or truncated if it is a
 * regular file; never through a symlink at the name); throws writeFailure(). */
void writeBytes(const std::string& path, const std::string& content);
/** Writes `content` to `path` through an exclusively created temporary file
 * beside it and a rename. */
void writeFileAtomic(const std::string& path, const std::string& content);
/** Creates a new empty temporary file beside `path` exclusively (mkstemp: an
 * unpredictable name, O_EXCL, never through a symlink) and returns its
 * path; the extension of `path` is kept last (OpenCV picks the format from
 * it). */
std::string exclusiveTempBeside(const std::string& path);

}  // namespace risknav::common
