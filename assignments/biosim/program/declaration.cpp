#include "biosim/program/course.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

#include "simlab/digits.h"
#include "simlab/integrators.h"

namespace biosim {

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument(what); }

std::string show(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

bool validName(const std::string& name) {
    if (name.empty() || name.size() > 40 || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
    for (const char c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
    }
    return true;
}

const Parameter* findParameter(const Declaration& declaration, const std::string& name) {
    for (const Parameter& p : declaration.parameters) {
        if (p.name == name) return &p;
    }
    return nullptr;
}

std::string parameterNames(const Declaration& declaration) {
    std::string names;
    for (const Parameter& p : declaration.parameters) names += (names.empty() ? "" : ", ") + p.name;
    return names.empty() ? "none" : names;
}

void checkSettingsNamed(const Declaration& declaration, const std::map<std::string, double>& settings,
                        const std::string& claim) {
    for (const auto& [name, value] : settings) {
        const Parameter* p = findParameter(declaration, name);
        if (!p) fail(claim + " sets '" + name + "', which is not a declared parameter");
        if (!(value >= p->min && value <= p->max)) {
            fail(claim + " sets " + name + " = " + show(value) + ", outside its range [" + show(p->min) + ", " +
                 show(p->max) + "]");
        }
    }
}

}  // namespace

void checkDeclaration(const Declaration& d) {
    if (!validName(d.program)) fail("the declaration's program name '" + d.program + "' is not a plain name");
    if (d.title.empty()) fail("the declaration has no title");
    std::set<std::string> names;
    for (const Parameter& p : d.parameters) {
        if (!validName(p.name)) fail("parameter name '" + p.name + "' is not a plain name (a letter, then letters, digits or _)");
        if (!names.insert(p.name).second) fail("parameter '" + p.name + "' is declared twice");
        if (p.unit.empty()) fail("parameter '" + p.name + "' has no unit (use \"1\" for a pure number)");
        if (!std::isfinite(p.min) || !std::isfinite(p.max) || !(p.min <= p.max)) {
            fail("parameter '" + p.name + "' has no finite range min <= max");
        }
        if (!(p.value >= p.min && p.value <= p.max)) {
            fail("parameter '" + p.name + "' defaults to " + show(p.value) + ", outside its range [" + show(p.min) +
                 ", " + show(p.max) + "]");
        }
    }
    if (d.columns.empty()) fail("the declaration samples no columns");
    std::set<std::string> columns;
    for (const Column& c : d.columns) {
        if (!validName(c.name)) fail("column name '" + c.name + "' is not a plain name");
        if (c.name == "time") fail("the course adds the time column; do not declare one");
        if (!columns.insert(c.name).second) fail("column '" + c.name + "' is declared twice");
        if (c.unit.empty()) fail("column '" + c.name + "' has no unit (use \"1\" for a pure number)");
    }
    for (const Rule& rule : d.rules) {
        if (rule.meaning.empty()) fail("a rule of the declaration says nothing of what it requires (its meaning)");
        if (!rule.holds) fail("the rule '" + rule.meaning + "' has no test (holds)");
    }
    if (d.claims.degreesOfFreedom < 0) fail("the claimed degrees of freedom are negative");
    checkSettingsNamed(d, d.claims.energyWhen, "the energy claim");
    checkSettingsNamed(d, d.claims.atRest, "the at-rest claim");
    for (const Conserved& c : d.claims.conserved) {
        if (!columns.count(c.column)) fail("the claim that '" + c.column + "' is conserved names no declared column");
        checkSettingsNamed(d, c.when, "the claim that " + c.column + " is conserved");
    }
    // The defaults and every claim's settings meet the rules (resolve names the one they break).
    resolve(d);
    resolve(d, d.claims.energyWhen);
    resolve(d, d.claims.atRest);
    simlab::validate(d.run);
}

double reachable(const Parameter& p, double target, const std::function<bool(double)>& allowed) {
    if (allowed(target)) return target;
    double good = p.value, bad = target;
    for (int i = 0; i < 40; ++i) {
        const double middle = (good + bad) / 2;
        (allowed(middle) ? good : bad) = middle;
    }
    return good;
}

double movedValue(const Parameter& p, const std::function<bool(double)>& allowed) {
    const double up = p.value + (p.max - p.value) / 2, down = p.value - (p.value - p.min) / 2;
    const double farTarget = up - p.value >= p.value - down ? up : down;
    const double far = reachable(p, farTarget, allowed);
    if (far == farTarget) return far;
    const double near = reachable(p, farTarget == up ? down : up, allowed);
    return std::abs(near - p.value) > std::abs(far - p.value) ? near : far;
}

double movedValue(const Declaration& declaration, const Parameter& p, const std::map<std::string, double>& others) {
    return movedValue(p, [&](double value) {
        std::map<std::string, double> set = others;
        set[p.name] = value;
        try {
            resolve(declaration, set);
            return true;
        } catch (const std::invalid_argument&) {
            return false;
        }
    });
}

std::vector<std::string> brokenRules(const Declaration& declaration, const Parameters& parameters) {
    std::vector<std::string> broken;
    for (const Rule& rule : declaration.rules) {
        if (!rule.holds || !rule.holds(parameters)) broken.push_back(rule.meaning);
    }
    return broken;
}

Parameters resolve(const Declaration& declaration, const std::map<std::string, double>& changes) {
    std::map<std::string, double> values;
    for (const Parameter& p : declaration.parameters) values[p.name] = p.value;
    for (const auto& [name, value] : changes) {
        const Parameter* p = findParameter(declaration, name);
        if (!p) fail("no parameter named '" + name + "'; the parameters are: " + parameterNames(declaration));
        if (!std::isfinite(value)) fail(name + " must be a finite number");
        if (!(value >= p->min && value <= p->max)) {
            fail(name + " = " + show(value) + " is outside its range [" + show(p->min) + ", " + show(p->max) +
                 "] " + p->unit);
        }
        values[name] = value;
    }
    Parameters resolved(std::move(values));
    const std::vector<std::string> broken = brokenRules(declaration, resolved);
    if (!broken.empty()) {
        std::string set;
        std::size_t k = 0;
        for (const auto& [name, value] : changes) {
            set += std::string(k == 0 ? "" : k + 1 == changes.size() ? " and " : ", ") + name + " = " + show(value);
            ++k;
        }
        const std::string who = changes.empty() ? "the defaults break" : changes.size() == 1 ? set + " breaks"
                                                                                          : set + " together break";
        fail(who + " a rule of the declaration: " + broken.front());
    }
    return resolved;
}

std::pair<std::string, double> parseSetting(const std::string& text) {
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0) fail("--set takes NAME=VALUE, got '" + text + "'");
    const std::string name = text.substr(0, equals);
    const std::string number = text.substr(equals + 1);
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size()) {
        fail("--set " + name + ": '" + number + "' is not a number");
    }
    return {name, value};
}

int columnIndex(const Declaration& declaration, const std::string& name) {
    for (std::size_t i = 0; i < declaration.columns.size(); ++i) {
        if (declaration.columns[i].name == name) return static_cast<int>(i);
    }
    fail("no column named '" + name + "'");
}

double agreementDigits(const Observed& a, const Observed& b) {
    double worst = simlab::kMaxDigits;
    if (a.q.empty() || b.q.empty()) return 0;
    using History = std::vector<std::vector<double>>;
    for (History Observed::*values : {&Observed::q, &Observed::u}) {
        const History& x = a.*values;
        const History& y = b.*values;
        double scale = 0;
        for (const std::vector<double>& v : y) {
            for (const double value : v) scale = std::max(scale, std::abs(value));
        }
        if (!(scale > 0)) scale = 1;
        if (x.back().size() != y.back().size()) return 0;
        for (std::size_t i = 0; i < y.back().size(); ++i) {
            worst = std::min(worst, simlab::accuracyDigits(x.back()[i], y.back()[i], scale));
        }
    }
    return worst;
}

}  // namespace biosim
