// Load one URDF with sdformat (Gazebo's URDF -> SDFormat converter) and print what it
// built, as one JSON line on stdout:
//   {"engine", "ok", "error", "bodies", "joints", "limits", "inertias"}
// the same report as urdflint/engines/probe.py. Compiled and run by
// urdflint/engines/sdformat.py: `sdformat_probe URDF [MEMORY_BYTES]`.
//
// sdformat prints its console messages (sdferr, sdfwarn) on stderr, as
// "Error [parser_urdf.cc:LINE] message"; the errors sdf::Root::Load returns are printed
// there too, as "Error [Root::Load] message". A model is "ok" when Load returned no
// error: Gazebo refuses to spawn a model whose Load returned errors. Everything else the
// process writes on stdout is moved to stderr, so stdout carries only the JSON line.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <sdf/Console.hh>
#include <sdf/Error.hh>
#include <sdf/Joint.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>

namespace
{
const double kUnbounded = 1e15;  // SDFormat's "no limit" defaults are -1e16 and 1e16

std::string Quote(const std::string &_text)
{
  std::ostringstream out;
  out << '"';
  for (unsigned char c : _text)
  {
    switch (c)
    {
      case '"': out << "\\\""; break;
      case '\\': out << "\\\\"; break;
      case '\n': out << "\\n"; break;
      case '\r': out << "\\r"; break;
      case '\t': out << "\\t"; break;
      default:
        if (c < 0x20)
        {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out << buffer;
        }
        else
        {
          out << c;
        }
    }
  }
  out << '"';
  return out.str();
}

std::string Number(double _value)
{
  if (!std::isfinite(_value))
    return "null";
  std::ostringstream out;
  out.precision(17);
  out << _value;
  return out.str();
}

std::string Bound(double _value)
{
  return std::fabs(_value) >= kUnbounded ? "null" : Number(_value);
}

void LimitMemory(const char *_bytes)
{
  const rlim_t limit = static_cast<rlim_t>(std::strtoull(_bytes, nullptr, 10));
  if (limit > 0)
  {
    struct rlimit both = {limit, limit};
    setrlimit(RLIMIT_AS, &both);
  }
}

// "bodies", "joints", "limits" and "inertias" of the built model, as JSON members.
std::string Describe(const sdf::Model &_model)
{
  std::ostringstream bodies, joints, limits, inertias;
  for (uint64_t i = 0; i < _model.LinkCount(); ++i)
  {
    const sdf::Link *link = _model.LinkByIndex(i);
    const std::string name = Quote(link->Name());
    const auto &matrix = link->Inertial().MassMatrix();
    const auto moments = matrix.PrincipalMoments();
    std::vector<double> sorted = {moments.X(), moments.Y(), moments.Z()};
    std::sort(sorted.begin(), sorted.end());
    bodies << (i ? "," : "") << name;
    inertias << (i ? "," : "") << name << ":[" << Number(matrix.Mass()) << ",["
             << Number(sorted[0]) << "," << Number(sorted[1]) << ","
             << Number(sorted[2]) << "]]";
  }
  bool first = true;
  for (uint64_t i = 0; i < _model.JointCount(); ++i)
  {
    const sdf::Joint *joint = _model.JointByIndex(i);
    joints << (i ? "," : "") << Quote(joint->Name());
    const char *kind = joint->Type() == sdf::JointType::REVOLUTE ? "revolute"
        : joint->Type() == sdf::JointType::PRISMATIC ? "prismatic" : nullptr;
    const sdf::JointAxis *axis = joint->Axis(0);
    if (kind == nullptr || axis == nullptr)
      continue;
    limits << (first ? "" : ",") << Quote(joint->Name()) << ":[\"" << kind << "\","
           << Bound(axis->Lower()) << "," << Bound(axis->Upper()) << "]";
    first = false;
  }
  return "\"bodies\":[" + bodies.str() + "],\"joints\":[" + joints.str() +
         "],\"limits\":{" + limits.str() + "},\"inertias\":{" + inertias.str() + "}";
}
}  // namespace

int main(int argc, char **argv)
{
  if (argc < 2)
  {
    std::cerr << "usage: " << argv[0] << " URDF [MEMORY_BYTES]\n";
    return 2;
  }
  if (argc > 2)
    LimitMemory(argv[2]);
  std::fflush(stdout);
  const int report = dup(1);
  dup2(2, 1);  // whatever the libraries print on stdout goes to stderr
  sdf::Console::Instance()->SetQuiet(false);

  sdf::Root root;
  const sdf::Errors errors = root.Load(argv[1]);
  std::string first;
  for (const sdf::Error &error : errors)
  {
    std::string text = error.Message();
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
      text.pop_back();
    if (first.empty())
      first = text;
    std::cerr << "Error [Root::Load] " << text << "\n";
  }
  const sdf::Model *model = root.Model();
  if (errors.empty() && model == nullptr)
    first = "the file has no model";
  std::string json = "{\"engine\":\"sdformat\",\"ok\":";
  json += first.empty() ? "true" : "false";
  json += ",\"error\":" + (first.empty() ? std::string("null") : Quote(first)) + ",";
  json += model ? Describe(*model)
                : "\"bodies\":[],\"joints\":[],\"limits\":{},\"inertias\":{}";
  json += "}\n";
  std::cerr.flush();
  std::fflush(stdout);
  if (write(report, json.data(), json.size()) < 0)
    return 3;
  return 0;
}
