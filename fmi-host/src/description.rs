//! What a host reads from `modelDescription.xml`: the GUID, the Co-Simulation model identifier,
//! the default experiment and each variable's name, value reference, causality and type.
//!
//! Parsed with `roxmltree`; errors name the element or variable and what is wrong with it.

use crate::Error;
use std::collections::HashMap;

/// The base type of a scalar variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarType {
    Real,
    Integer,
    Boolean,
    String,
    Enumeration,
}

/// FMI 2.0 causality.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    Local,
    Independent,
}

/// One `<ScalarVariable>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    pub name: String,
    pub vr: u32,
    pub causality: Causality,
    pub ty: VarType,
}

/// `<DefaultExperiment>`; each attribute is optional in FMI 2.0.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: Option<f64>,
    pub stop_time: Option<f64>,
    pub step_size: Option<f64>,
}

/// The parts of a model description a Co-Simulation host needs.
#[derive(Debug, Clone)]
pub struct ModelDescription {
    pub guid: String,
    pub model_identifier: String,
    pub default_experiment: Option<DefaultExperiment>,
    variables: Vec<Variable>,
    by_name: HashMap<String, usize>,
}

impl ModelDescription {
    /// Reads `xml`; errors name what is missing or malformed.
    pub fn parse(xml: &str) -> Result<Self, Error> {
        let document = roxmltree::Document::parse(xml).map_err(|e| invalid(&e.to_string()))?;
        let root = document.root_element();
        if !root.has_tag_name("fmiModelDescription") {
            return Err(invalid("no <fmiModelDescription>"));
        }
        let guid = required(root, "guid")?;
        let cs = child(root, "CoSimulation").ok_or_else(|| invalid("no <CoSimulation>"))?;
        let model_identifier = required(cs, "modelIdentifier")?;
        let default_experiment = child(root, "DefaultExperiment")
            .map(default_experiment)
            .transpose()?;
        let variables = child(root, "ModelVariables")
            .into_iter()
            .flat_map(|list| list.children().filter(|n| n.has_tag_name("ScalarVariable")))
            .map(variable)
            .collect::<Result<Vec<_>, _>>()?;
        let mut by_name = HashMap::with_capacity(variables.len());
        for (i, v) in variables.iter().enumerate() {
            if by_name.insert(v.name.clone(), i).is_some() {
                return Err(invalid(&format!("variable {:?} is declared twice", v.name)));
            }
        }
        Ok(Self {
            guid,
            model_identifier,
            default_experiment,
            variables,
            by_name,
        })
    }

    /// Every variable, in the order of the description.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// The variable `name`.
    pub fn variable(&self, name: &str) -> Result<&Variable, Error> {
        self.by_name
            .get(name)
            .map(|&i| &self.variables[i])
            .ok_or_else(|| Error::UnknownVariable {
                model: self.model_identifier.clone(),
                name: name.to_string(),
            })
    }

    /// The outputs of type `ty`, in the order of the description.
    pub fn outputs(&self, ty: VarType) -> impl Iterator<Item = &Variable> {
        self.variables
            .iter()
            .filter(move |v| v.causality == Causality::Output && v.ty == ty)
    }
}

fn invalid(reason: &str) -> Error {
    Error::ModelDescription(reason.to_string())
}

type Node<'a> = roxmltree::Node<'a, 'a>;

/// The first child element `name` of `parent`.
fn child<'a>(parent: Node<'a>, name: &str) -> Option<Node<'a>> {
    parent.children().find(|n| n.has_tag_name(name))
}

/// Attribute `key` of `element`, which must have it.
fn required(element: Node<'_>, key: &str) -> Result<String, Error> {
    element
        .attribute(key)
        .map(str::to_string)
        .ok_or_else(|| invalid(&format!("<{}> has no {key}", element.tag_name().name())))
}

fn default_experiment(element: Node<'_>) -> Result<DefaultExperiment, Error> {
    let number = |key: &str| -> Result<Option<f64>, Error> {
        element
            .attribute(key)
            .map(|text| {
                text.trim().parse().map_err(|_| {
                    invalid(&format!(
                        "<DefaultExperiment> {key} = {text:?} is not a number"
                    ))
                })
            })
            .transpose()
    };
    Ok(DefaultExperiment {
        start_time: number("startTime")?,
        stop_time: number("stopTime")?,
        step_size: number("stepSize")?,
    })
}

/// One `<ScalarVariable>`: its attributes and the name of its type element.
fn variable(element: Node<'_>) -> Result<Variable, Error> {
    let name = element
        .attribute("name")
        .ok_or_else(|| invalid("a <ScalarVariable> has no name"))?
        .to_string();
    let vr_text = element
        .attribute("valueReference")
        .ok_or_else(|| invalid(&format!("variable {name:?} has no valueReference")))?;
    let vr = vr_text.trim().parse().map_err(|_| {
        invalid(&format!(
            "variable {name:?}: valueReference = {vr_text:?} is not an unsigned 32-bit integer"
        ))
    })?;
    let causality_text = element.attribute("causality").unwrap_or("local");
    let causality = causality_of(causality_text).ok_or_else(|| {
        invalid(&format!(
            "variable {name:?}: unknown causality {causality_text:?}"
        ))
    })?;
    let type_name = element
        .children()
        .find(roxmltree::Node::is_element)
        .map_or("", |n| n.tag_name().name());
    let ty = type_of(type_name).ok_or_else(|| {
        invalid(&format!(
            "variable {name:?}: unknown type element <{type_name}>"
        ))
    })?;
    Ok(Variable {
        name,
        vr,
        causality,
        ty,
    })
}

fn causality_of(text: &str) -> Option<Causality> {
    Some(match text {
        "parameter" => Causality::Parameter,
        "calculatedParameter" => Causality::CalculatedParameter,
        "input" => Causality::Input,
        "output" => Causality::Output,
        "local" => Causality::Local,
        "independent" => Causality::Independent,
        _ => return None,
    })
}

fn type_of(element: &str) -> Option<VarType> {
    Some(match element {
        "Real" => VarType::Real,
        "Integer" => VarType::Integer,
        "Boolean" => VarType::Boolean,
        "String" => VarType::String,
        "Enumeration" => VarType::Enumeration,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const XML: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="M" guid="{1234}">
  <CoSimulation modelIdentifier='Model' canGetAndSetFMUstate="true"/>
  <DefaultExperiment startTime="0" stopTime="0.5" stepSize="1e-3"/>
  <ModelVariables>
    <!-- index 1 -->
    <ScalarVariable name="left.Q" valueReference="0" description="a &gt; b" causality="input" variability="continuous">
      <Real start="1"/>
    </ScalarVariable>
    <ScalarVariable name="n&quot;" valueReference="7" causality="output">
      <Integer/>
    </ScalarVariable>
    <ScalarVariable name="profile" valueReference="2" causality="parameter" variability="fixed">
      <String start="a&amp;lt;b"/>
    </ScalarVariable>
  </ModelVariables>
</fmiModelDescription>"#;

    #[test]
    fn reads_identity_experiment_and_variables() {
        let md = ModelDescription::parse(XML).unwrap();
        assert_eq!(
            (md.guid.as_str(), md.model_identifier.as_str()),
            ("{1234}", "Model")
        );
        let de = md.default_experiment.unwrap();
        assert_eq!(
            (de.start_time, de.stop_time, de.step_size),
            (Some(0.0), Some(0.5), Some(1e-3))
        );
        let q = md.variable("left.Q").unwrap();
        assert_eq!(
            (q.vr, q.causality, q.ty),
            (0, Causality::Input, VarType::Real)
        );
        let n = md.variable("n\"").unwrap();
        assert_eq!(
            (n.vr, n.causality, n.ty),
            (7, Causality::Output, VarType::Integer)
        );
        assert_eq!(md.variable("profile").unwrap().ty, VarType::String);
        assert_eq!(md.outputs(VarType::Integer).count(), 1);
        assert_eq!(
            md.variable("right.Q").unwrap_err().to_string(),
            "Model has no variable \"right.Q\""
        );
    }

    #[test]
    fn malformed_descriptions_say_what_is_wrong() {
        let bad_vr = XML.replace("valueReference=\"7\"", "valueReference=\"-7\"");
        let no_cs = XML.replace("<CoSimulation", "<ModelExchange");
        let twice = XML.replace("name=\"profile\"", "name=\"left.Q\"");
        let no_guid = XML.replace("guid=\"{1234}\"", "");
        for (xml, reason) in [
            (
                bad_vr.as_str(),
                "variable \"n\\\"\": valueReference = \"-7\" is not an unsigned 32-bit integer",
            ),
            (no_cs.as_str(), "no <CoSimulation>"),
            (twice.as_str(), "variable \"left.Q\" is declared twice"),
            ("<fmi/>", "no <fmiModelDescription>"),
            (no_guid.as_str(), "<fmiModelDescription> has no guid"),
        ] {
            let error = ModelDescription::parse(xml).unwrap_err().to_string();
            assert!(
                error.ends_with(reason),
                "{error:?} does not end with {reason:?}"
            );
        }
    }
}
