#include "RefractaSceneJson.h"

#include <cmath>
#include <sstream>

namespace RefractaRender
{
namespace
{
// "a, b, c": the names of a set, in its order.
std::string Join(const std::set<std::string>& names)
{
  std::string list;
  for (const auto& name : names)
  {
    list += (list.empty() ? "" : ", ") + name;
  }
  return list;
}

// A number that must be finite and in [lo, hi] (printed exactly: [1, 268435456], not
// [1, 2.68435e+08]).
double CheckedNumber(const json& v, const std::string& path, double lo, double hi)
{
  if (!v.is_number())
  {
    Fail(path, "must be a number");
  }
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi)
  {
    auto print = [](double x)
    {
      std::ostringstream os;
      if (std::abs(x) < 1e15 && x == std::floor(x))
      {
        os << static_cast<long long>(x);
      }
      else
      {
        os << x;
      }
      return os.str();
    };
    Fail(path, "value " + print(d) + " is out of range [" + print(lo) + ", " + print(hi) + "]");
  }
  return d;
}

// `text` for a message: at most 80 characters (a 1 MB string was echoed whole).
std::string Quoted(const std::string& text)
{
  return "'" + (text.size() > 80 ? text.substr(0, 77) + "..." : text) + "'";
}
}

bool IsInteger(const json& v)
{
  return v.is_number_integer() ||
    (v.is_number_float() && std::isfinite(v.get<double>()) &&
      v.get<double>() == std::floor(v.get<double>()));
}

[[noreturn]] void Fail(const std::string& path, const std::string& what)
{
  throw SceneError(path + ": " + what);
}

void CheckKeys(const json& object, const std::string& path, const std::set<std::string>& allowed)
{
  if (!object.is_object())
  {
    Fail(path, "must be a JSON object");
  }
  for (auto it = object.begin(); it != object.end(); ++it)
  {
    if (!allowed.count(it.key()))
    {
      Fail(path + "." + it.key(), "unknown key (allowed here: " + Join(allowed) + ")");
    }
  }
}

double Number(const json& object, const std::string& key, const std::string& path, double fallback,
  double lo, double hi)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  return CheckedNumber(object[key], path + "." + key, lo, hi);
}

int Integer(
  const json& object, const std::string& key, const std::string& path, int fallback, int lo, int hi)
{
  if (object.contains(key) && object[key].is_number() && !IsInteger(object[key]))
  {
    Fail(path + "." + key, "must be an integer");
  }
  return static_cast<int>(Number(object, key, path, fallback, lo, hi));
}

std::vector<double> Vector(const json& object, const std::string& key, const std::string& path,
  std::vector<double> fallback, size_t size, double lo, double hi)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  const json& v = object[key];
  if (!v.is_array() || v.size() != size)
  {
    Fail(path + "." + key, "must be an array of " + std::to_string(size) + " numbers");
  }
  std::vector<double> out;
  for (size_t i = 0; i < size; ++i)
  {
    out.push_back(CheckedNumber(v[i], path + "." + key + "[" + std::to_string(i) + "]", lo, hi));
  }
  return out;
}

std::vector<int> IntegerVector(const json& object, const std::string& key, const std::string& path,
  std::vector<int> fallback, size_t size, int lo, int hi)
{
  const auto values = Vector(object, key, path, {}, size, lo, hi);
  if (values.empty())
  {
    return fallback;
  }
  std::vector<int> out;
  for (size_t i = 0; i < size; ++i)
  {
    if (!IsInteger(object[key][i]))
    {
      Fail(path + "." + key + "[" + std::to_string(i) + "]", "must be an integer");
    }
    out.push_back(static_cast<int>(values[i]));
  }
  return out;
}

std::vector<double> Bounds(const json& object, const std::string& key, const std::string& path)
{
  auto bounds = Vector(object, key, path, {}, 6, -1e30, 1e30);
  for (size_t a = 0; a < bounds.size() / 2; ++a)
  {
    if (!(bounds[2 * a] < bounds[2 * a + 1]))
    {
      Fail(path + "." + key, "every min must be below its max");
    }
  }
  return bounds;
}

std::string String(const json& object, const std::string& key, const std::string& path,
  const std::string& fallback, const std::set<std::string>& choices)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  if (!object[key].is_string())
  {
    Fail(path + "." + key, "must be a string");
  }
  const std::string s = object[key].get<std::string>();
  if (!choices.empty() && !choices.count(s))
  {
    Fail(path + "." + key, Quoted(s) + " is not one of: " + Join(choices));
  }
  return s;
}

bool Boolean(const json& object, const std::string& key, const std::string& path, bool fallback)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  if (!object[key].is_boolean())
  {
    Fail(path + "." + key, "must be true or false");
  }
  return object[key].get<bool>();
}
}
