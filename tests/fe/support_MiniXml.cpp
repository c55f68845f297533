// Implements the test helpers of fe/support_MiniXml.h (documented there).
#include "fe/support_MiniXml.h"

#include <cctype>

namespace jawmesh::test {
namespace {

class Parser {
public:
    explicit Parser(const std::string& s) : s_(s) {}

    std::unique_ptr<XmlNode> document() {
        skipMisc();
        if (s_.compare(i_, 5, "<?xml") == 0) {
            i_ = s_.find("?>", i_);
            if (i_ == std::string::npos) fail("unterminated declaration");
            i_ += 2;
        }
        skipMisc();
        auto root = element();
        skipMisc();
        if (i_ != s_.size()) fail("content after the root element");
        return root;
    }

private:
    [[noreturn]] void fail(const std::string& why) { throw std::runtime_error("XML offset " + std::to_string(i_) + ": " + why); }
    void skipSpace() {
        while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
    }
    void skipMisc() {
        for (;;) {
            skipSpace();
            if (s_.compare(i_, 4, "<!--") != 0) return;
            const auto end = s_.find("-->", i_ + 4);
            if (end == std::string::npos) fail("unterminated comment");
            i_ = end + 3;
        }
    }
    std::string name() {
        const std::size_t start = i_;
        while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == '-' || s_[i_] == ':' || s_[i_] == '.')) ++i_;
        if (i_ == start) fail("expected a name");
        return s_.substr(start, i_ - start);
    }
    std::unique_ptr<XmlNode> element() {
        if (i_ >= s_.size() || s_[i_] != '<') fail("expected '<'");
        ++i_;
        auto node = std::make_unique<XmlNode>();
        node->name = name();
        for (;;) {
            skipSpace();
            if (i_ >= s_.size()) fail("unterminated tag <" + node->name + ">");
            if (s_.compare(i_, 2, "/>") == 0) {
                i_ += 2;
                return node;
            }
            if (s_[i_] == '>') {
                ++i_;
                break;
            }
            const std::string key = name();
            skipSpace();
            if (i_ >= s_.size() || s_[i_] != '=') fail("attribute without '='");
            ++i_;
            skipSpace();
            if (i_ >= s_.size() || s_[i_] != '"') fail("unquoted attribute value");
            const auto end = s_.find('"', i_ + 1);
            if (end == std::string::npos) fail("unterminated attribute value");
            if (!node->attributes.emplace(key, s_.substr(i_ + 1, end - i_ - 1)).second) fail("duplicated attribute " + key);
            i_ = end + 1;
        }
        for (;;) {
            if (i_ >= s_.size()) fail("<" + node->name + "> is never closed");
            if (s_.compare(i_, 4, "<!--") == 0) {
                skipMisc();
            } else if (s_.compare(i_, 2, "</") == 0) {
                i_ += 2;
                if (name() != node->name) fail("mismatched closing tag for <" + node->name + ">");
                skipSpace();
                if (i_ >= s_.size() || s_[i_] != '>') fail("malformed closing tag");
                ++i_;
                return node;
            } else if (s_[i_] == '<') {
                node->children.push_back(element());
            } else {
                const auto end = s_.find('<', i_);
                if (end == std::string::npos) fail("text never closed");
                const std::string text = s_.substr(i_, end - i_);
                if (text.find('&') != std::string::npos || text.find('>') != std::string::npos) fail("unescaped character in text");
                node->text += text;
                i_ = end;
            }
        }
    }

    const std::string& s_;
    std::size_t i_ = 0;
};

}  // namespace

std::unique_ptr<XmlNode> parseXml(const std::string& text) { return Parser(text).document(); }

}  // namespace jawmesh::test
