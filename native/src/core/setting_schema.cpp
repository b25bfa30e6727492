// How a setting's entry is shown (default, range) and how tables are composed and searched.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "core/setting_schema.h"

#include <iomanip>
#include <sstream>

namespace ss {

namespace {

std::string shown(double v) {
    std::ostringstream s;
    s << std::setprecision(12) << v;  // 16777216 whole, 0.0001 as written
    return s.str();
}

}  // namespace

std::vector<std::string> SettingSpec::choiceList() const {
    std::vector<std::string> out;
    std::string all = choices;
    size_t start = 0;
    while (start <= all.size() && !all.empty()) {
        size_t end = all.find('|', start);
        if (end == std::string::npos) end = all.size();
        out.push_back(all.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

std::string SettingSpec::defaultText() const {
    if (renderDefault) return renderDefault;
    switch (type) {
        case SettingType::Int:
        case SettingType::Float: return shown(fallback);
        case SettingType::Bool: return fallback != 0.0 ? "on" : "off";
        case SettingType::Choice: return choiceList().empty() ? "" : choiceList().front();
        case SettingType::Text: return "";
    }
    return "";
}

std::string SettingSpec::rangeText() const {
    switch (type) {
        case SettingType::Int:
        case SettingType::Float: return (zeroIsDefault ? "0 or " : "") + shown(lo) + ".." + shown(hi);
        case SettingType::Bool: return "on/off";
        case SettingType::Choice: return choices;
        case SettingType::Text: return "";
    }
    return "";
}

SettingTable composed(SettingTable table, const SettingTable& more) {
    for (const SettingSpec& s : more)
        if (!findSetting(table, s.key)) table.push_back(s);
    return table;
}

const SettingSpec* findSetting(const SettingTable& table, const std::string& key) {
    for (const SettingSpec& s : table)
        if (key == s.key) return &s;
    return nullptr;
}

std::vector<std::string> userKeys(const SettingTable& table) {
    std::vector<std::string> out;
    for (const SettingSpec& s : table)
        if (!s.debug()) out.push_back(s.key);
    return out;
}

}  // namespace ss
