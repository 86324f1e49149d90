// Session files from the viewer (save, load: one commit) and copy-as-command.

#include <cstdio>

#include "core/error.h"
#include "core/file_io.h"
#include "picture/picture.h"
#include "viewer/logic/data_change.h"
#include "viewer/viewer_app_impl.h"
#include "viewer/window.h"

namespace amrvk::viewer {

session::Session ViewerApp::currentSession() const {
    session::Session s = mState;
    s.input = fs::absolute(s.input).lexically_normal().string();
    return s;
}

void ViewerApp::saveSessionFile(const fs::path& file) {
    session::saveSession(file, currentSession());
    mPanel.message = "saved " + file.string();
}

void ViewerApp::loadSessionFile(const fs::path& file) {
    session::Session s = session::loadSession(file);
    const DataChangeCheck change = dataChange(mState, s);
    AMRVK_CHECK(change.kind != DataChange::Other, file.string(), ": ", change.reason,
                "; open it with amrvk view --session ", file.string());
    scene::validateSettings(s.settings);
    s.input = mState.input;  // the same data set (compared as absolute paths)
    if (change.kind == DataChange::Rescale) {
        // Read again on the session's scale, with its structure, settings and TF (in that scale's
        // units) at once: when anything fails nothing of the session is taken.
        reloadData(s, false);
    } else {
        // Structure, TF (with the meaning its colours were saved with) and settings in one commit:
        // one build and one majorant pass; when the structure cannot be built nothing is taken.
        picture::PictureEdit e{.tf = TfEditor::editable(s.tf), .tfColors = s.tfColors, .settings = s.settings};
        if (!(s.structure == mState.structure)) e.structure = s.structure;
        commit(e);
        mState.spp = s.spp;
        mState.cameraPath = s.cameraPath;  // (a rescale takes it with the rest of s)
        mTfHistory.push(mState.tf);
    }
    stopPath();
    mPathPreview.frame.reset();
    mPanel.message = "loaded " + file.string();
}

void ViewerApp::copyCommand() {
    const session::Session s = currentSession();
    // The TF beside the session file's default place, so the command does not depend on the viewer.
    const fs::path tfFile = fs::absolute(mPanel.tfPath);
    writeFileAtomic(tfFile, TfEditor(mState.tf).toParaViewJson(tfFile.stem().string()));
    const std::string line = session::renderCommandLine(s, tfFile.string(), "amrvk.png");
    if (mWindow) mWindow->setClipboard(line);
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    mPanel.message = "command copied (TF in " + tfFile.string() + ")";
}

}  // namespace amrvk::viewer
