#include "calibration/lamp_urdf.hpp"

#include <cstdio>
#include <stdexcept>

#include <tinyxml2.h>

namespace wysiwyf::vision::calibration {

namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

void load(XMLDocument& doc, const std::string& path) {
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error(path + ": cannot read it as XML (" + std::string(doc.ErrorStr()) + ")");
  if (!doc.FirstChildElement("robot")) throw std::runtime_error(path + ": no <robot> element; expected a URDF");
}

// The <joint> whose <child link=...> is `child`, or nullptr.
XMLElement* joint_of(XMLDocument& doc, const std::string& child) {
  for (XMLElement* j = doc.FirstChildElement("robot")->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    const XMLElement* c = j->FirstChildElement("child");
    if (c && c->Attribute("link") && child == c->Attribute("link")) return j;
  }
  return nullptr;
}

}  // namespace

std::string joint_parent(const std::string& urdf_path, const std::string& child_link) {
  XMLDocument doc;
  load(doc, urdf_path);
  const XMLElement* joint = joint_of(doc, child_link);
  const XMLElement* parent = joint ? joint->FirstChildElement("parent") : nullptr;
  if (!parent || !parent->Attribute("link"))
    throw std::runtime_error(urdf_path + ": no joint with child link '" + child_link + "' and a parent link");
  return parent->Attribute("link");
}

void write_lamps_urdf(const std::string& urdf_in, const std::string& urdf_out,
                      const std::map<std::string, Eigen::Vector3d>& parent_p_child, const std::string& note) {
  XMLDocument doc;
  load(doc, urdf_in);
  for (const auto& [child, p] : parent_p_child) {
    XMLElement* joint = joint_of(doc, child);
    if (!joint) throw std::runtime_error(urdf_in + ": no joint with child link '" + child + "'");
    if (joint->Attribute("type") && std::string(joint->Attribute("type")) != "fixed")
      throw std::runtime_error(urdf_in + ": the joint of '" + child + "' is " + joint->Attribute("type") +
                               "; expected fixed");
    XMLElement* origin = joint->FirstChildElement("origin");
    if (!origin) origin = joint->InsertNewChildElement("origin");
    char xyz[96];
    std::snprintf(xyz, sizeof xyz, "%.6f %.6f %.6f", p.x(), p.y(), p.z());
    origin->SetAttribute("xyz", xyz);
  }
  std::string comment = " " + note + " ";
  for (std::size_t i; (i = comment.find("--")) != std::string::npos;) comment.replace(i, 2, "- ");  // (XML comments)
  tinyxml2::XMLComment* said = doc.NewComment(comment.c_str());
  if (doc.FirstChild() && doc.FirstChild()->ToDeclaration())
    doc.InsertAfterChild(doc.FirstChild(), said);
  else
    doc.InsertFirstChild(said);
  if (doc.SaveFile(urdf_out.c_str()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error("cannot write '" + urdf_out + "'");
}

}  // namespace wysiwyf::vision::calibration
