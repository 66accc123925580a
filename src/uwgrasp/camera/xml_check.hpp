#pragma once
// Internal to camera/: a well-formedness check of XML text before OpenCV's FileStorage reads it.
#include <string>

namespace uwgrasp::camera {

// Throws Error naming `file` unless `text` is well-formed XML of the kind FileStorage writes: an
// optional complete <?xml ...?> declaration, comments, and elements that nest and close, with
// quoted attributes. OpenCV 4.6's parser reads null pointers on truncated declarations and
// tags (found by fuzz/).
void check_xml(const std::string& text, const std::string& file);

}  // namespace uwgrasp::camera
