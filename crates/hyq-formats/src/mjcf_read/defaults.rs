//! MJCF default classes: `<default class="…">` nested in each other, each holding attribute
//! templates per element type (`<joint>`, `<geom>`, `<position>`, …). An element takes the
//! templates of its class and of every class above it, the innermost winning, then its own
//! attributes. Its class is its `class` attribute, else the `childclass` of the nearest body
//! above that has one, else the top class (`main`).

use std::collections::HashMap;

use super::elem::{Elem, MjcfReadError};

/// The name of the top default class.
pub(crate) const MAIN: &str = "main";

/// Element types a default class may hold templates for; anything else in a `<default>` is
/// refused.
const TEMPLATES: &[&str] = &[
    "joint",
    "geom",
    "site",
    "camera",
    "light",
    "mesh",
    "material",
    "position",
    "motor",
    "general",
    "velocity",
    "pair",
    "equality",
    "tendon",
    "texture",
    "hfield",
    "freejoint",
];

#[derive(Debug, Default)]
struct Class {
    parent: Option<String>,
    templates: HashMap<String, Vec<(String, String)>>,
}

/// Every default class of a model.
#[derive(Debug)]
pub(crate) struct Defaults {
    classes: HashMap<String, Class>,
}

impl Defaults {
    /// The classes of the `<default>` elements among `top` (the children of `<mujoco>`).
    pub(crate) fn read(top: &[Elem]) -> Result<Self, MjcfReadError> {
        let mut classes: HashMap<String, Class> = HashMap::new();
        classes.insert(MAIN.to_owned(), Class::default());
        for d in top.iter().filter(|e| e.tag == "default") {
            // A top-level <default> is the main class whatever it is called.
            if let Some(name) = d.get("class")
                && name != MAIN
            {
                return Err(d.error(format!(
                    "the top-level default class is {name:?}; MuJoCo names it \"main\""
                )));
            }
            read_class(d, MAIN, &mut classes)?;
        }
        Ok(Self { classes })
    }

    /// Refuses a class name that is not defined.
    pub(crate) fn check_class(&self, elem: &Elem, class: &str) -> Result<(), MjcfReadError> {
        if self.classes.contains_key(class) {
            Ok(())
        } else {
            Err(elem.error(format!("no default class named {class:?}")))
        }
    }

    /// The attributes class `class` gives elements of type `tag`, outermost class first (a
    /// later entry of the same name wins).
    pub(crate) fn template(&self, class: &str, tag: &str) -> Vec<(String, String)> {
        let mut chain = Vec::new();
        let mut at = Some(class);
        // Classes are a tree (names are unique and parents are defined before children), so
        // this ends; the cap is a second guard.
        while let Some(name) = at {
            let Some(c) = self.classes.get(name) else {
                break;
            };
            chain.push(c);
            at = c.parent.as_deref();
            if chain.len() > self.classes.len() {
                break;
            }
        }
        let mut out: Vec<(String, String)> = Vec::new();
        for c in chain.iter().rev() {
            for (k, v) in c.templates.get(tag).into_iter().flatten() {
                match out.iter_mut().find(|(ok, _)| ok == k) {
                    Some(slot) => slot.1.clone_from(v),
                    None => out.push((k.clone(), v.clone())),
                }
            }
        }
        out
    }

    /// The class an element takes: its own `class`, else the inherited `childclass`.
    pub(crate) fn class_of<'a>(
        &self,
        elem: &'a Elem,
        inherited: &'a str,
    ) -> Result<&'a str, MjcfReadError> {
        let class = elem.get("class").unwrap_or(inherited);
        self.check_class(elem, class)?;
        Ok(class)
    }
}

fn read_class(
    d: &Elem,
    name: &str,
    classes: &mut HashMap<String, Class>,
) -> Result<(), MjcfReadError> {
    if let Some((k, _)) = d.attrs.iter().find(|(k, _)| k != "class") {
        return Err(d.error(format!("attribute `{k}` is not understood")));
    }
    for child in &d.children {
        if child.tag == "default" {
            let Some(sub) = child.get("class") else {
                return Err(child.error("a nested <default> needs a `class`"));
            };
            if classes.contains_key(sub) {
                return Err(child.error(format!(
                    "default class {sub:?} is defined twice (a class cannot contain or \
                     repeat itself)"
                )));
            }
            classes.insert(
                sub.to_owned(),
                Class {
                    parent: Some(name.to_owned()),
                    templates: HashMap::new(),
                },
            );
            read_class(child, sub, classes)?;
            continue;
        }
        if !TEMPLATES.contains(&child.tag.as_str()) {
            return Err(child.error("is not an element a default class can hold"));
        }
        if child.get("class").is_some() {
            return Err(child.error("a template inside a default class takes no `class`"));
        }
        let templates = &mut classes
            .get_mut(name)
            .ok_or_else(|| d.error("internal: class missing"))?
            .templates;
        let slot = templates.entry(child.tag.clone()).or_default();
        for (k, v) in &child.attrs {
            match slot.iter_mut().find(|(sk, _)| sk == k) {
                Some(s) => s.1.clone_from(v),
                None => slot.push((k.clone(), v.clone())),
            }
        }
    }
    Ok(())
}
