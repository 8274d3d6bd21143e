// The description's five parts, project.toml, read as data: whether each is there with substance, and if not, what
// to do. Its bytes are the student's; the description test judges what this reads (visible.cpp), and tests/fuzz
// reads it as that test does.
#pragma once

#include <cctype>
#include <cmath>
#include <set>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "biosim/grading/observations.h"

namespace biosim::testing {

/// Words in a text (runs of letters or digits).
inline int wordCount(const std::string& text) {
    int words = 0;
    bool inWord = false;
    for (const char c : text) {
        const bool letter = std::isalnum(static_cast<unsigned char>(c)) != 0;
        if (letter && !inWord) ++words;
        inWord = letter;
    }
    return words;
}

/// True if a text is still the template's placeholder.
inline bool isPlaceholder(const std::string& text) { return text.find("TODO") != std::string::npos; }

/// One of the five parts of project.toml: whether it is there with substance, and if not, what to do.
struct Part {
    std::string name;
    std::string missing;  ///< empty when the part is complete
};

inline Part schematicPart(const toml::table& t, const Schematic& model) {
    Part part{"schematic", ""};
    const toml::array* bodies = t["schematic"]["bodies"].as_array();
    const toml::array* points = t["schematic"]["points"].as_array();
    if (!bodies || bodies->empty() || !points || points->empty()) {
        part.missing = "[schematic] lists the model's points and bodies: points = [...], bodies = [...]";
        return part;
    }
    std::set<std::string> listed, built;
    for (const auto& b : *bodies) listed.insert(b.value_or(std::string()));
    for (const SchematicBody& b : model.bodies) built.insert(b.name);
    if (listed != built) {
        std::string names;
        for (const std::string& n : built) names += (names.empty() ? "" : ", ") + n;
        part.missing = "[schematic] bodies must name the bodies the model builds (" + names + ")";
    }
    return part;
}

inline Part paragraphPart(const toml::table& t) {
    const std::string text = t["description"]["text"].value_or(std::string());
    if (isPlaceholder(text) || wordCount(text) < 40) {
        return {"description", "[description] text is a paragraph of at least 40 words about the system (has " +
                                   std::to_string(wordCount(text)) + ")"};
    }
    return {"description", ""};
}

inline Part considerationsPart(const toml::table& t) {
    const toml::array* list = t["considerations"]["list"].as_array();
    int substantial = 0;
    if (list) {
        for (const auto& item : *list) {
            const std::string text = item.value_or(std::string());
            if (!isPlaceholder(text) && wordCount(text) >= 3) ++substantial;
        }
    }
    if (substantial < 3) {
        return {"considerations", "[considerations] list holds at least 3 modelling considerations of 3 words or more (has " +
                                      std::to_string(substantial) + ")"};
    }
    return {"considerations", ""};
}

inline Part questionPart(const toml::table& t) {
    const std::string text = t["question"]["text"].value_or(std::string());
    const auto answer = t["question"]["answer"].value<double>();
    if (isPlaceholder(text) || wordCount(text) < 6 || text.find('?') == std::string::npos) {
        return {"question", "[question] text asks an interesting question, of 6 words or more, ending in '?'"};
    }
    if (!answer || !std::isfinite(*answer) || t["question"]["unit"].value_or(std::string()).empty()) {
        return {"question", "[question] gives the answer your program computes (answer = <number>, unit = \"...\")"};
    }
    return {"question", ""};
}

inline Part experimentsPart(const toml::table& t, const std::vector<ExperimentInfo>& inCode, int minimum) {
    const toml::array* list = t["experiment"].as_array();
    std::set<std::string> described;
    if (list) {
        for (const auto& item : *list) {
            const toml::table* e = item.as_table();
            if (!e) continue;
            const std::string name = (*e)["name"].value_or(std::string());
            const std::string shows = (*e)["shows"].value_or(std::string());
            if (!name.empty() && !isPlaceholder(shows) && wordCount(shows) >= 4) described.insert(name);
        }
    }
    std::set<std::string> coded;
    for (const ExperimentInfo& e : inCode) coded.insert(e.name);
    if (static_cast<int>(described.size()) < minimum) {
        return {"experiments", "[[experiment]] entries describe at least " + std::to_string(minimum) +
                                   " of your experiments (name = ..., shows = \"what it validates\")"};
    }
    for (const std::string& name : described) {
        if (!coded.count(name)) return {"experiments", "experiment '" + name + "' is described but experiments() has none of that name"};
    }
    for (const std::string& name : coded) {
        if (!described.count(name)) return {"experiments", "experiment '" + name + "' is in experiments() but not described in project.toml"};
    }
    return {"experiments", ""};
}

}  // namespace biosim::testing
