// A strict little XML reader for the tests (elements, attributes, text, comments, the declaration):
// enough to check that the FEBio files are well-formed and to walk them. Throws on malformed input.
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace jawmesh::test {

struct XmlNode {
    std::string name;
    std::map<std::string, std::string> attributes;
    std::string text;
    std::vector<std::unique_ptr<XmlNode>> children;
    /// Children named `name`.
    std::vector<const XmlNode*> all(const std::string& childName) const {
        std::vector<const XmlNode*> out;
        for (const auto& c : children)
            if (c->name == childName) out.push_back(c.get());
        return out;
    }
    const XmlNode& one(const std::string& childName) const {
        const auto found = all(childName);
        if (found.size() != 1) throw std::runtime_error("expected one <" + childName + "> in <" + name + ">");
        return *found[0];
    }
};

/// Parses a whole document; throws std::runtime_error naming the offset for anything malformed
/// (unclosed or mismatched tags, unquoted or duplicated attributes, text outside the root, ...).
std::unique_ptr<XmlNode> parseXml(const std::string& text);

}  // namespace jawmesh::test
