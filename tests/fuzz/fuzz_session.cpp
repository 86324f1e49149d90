// Session files (src/session/session.cpp): parseSession on the text, as `render --session` and
// the viewer's "load session" read it; a session that parses is written back (sessionJson), read
// again, and turned into its amrvk render command line. Input: the JSON text.
#include "fuzz_common.h"
#include "session/picture_description.h"
#include "session/session.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expectOnlyAmrvkErrors("session", [&] {
        const session::Session s = session::parseSession(text, "fuzz.json");
        const session::Session back = session::parseSession(session::sessionJson(s), "back.json");
        (void)session::renderCommandLine(back, "tf.json", "out.png");
        (void)s.tf.merged();
    });
    return 0;
}
