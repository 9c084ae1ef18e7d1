//! A tiny element tree rendered through quick-xml, shared by the XML writers (SDFormat, MJCF,
//! package.xml) and parsed back by the readers (SDFormat of resumed runs, the SDF/URDF asset
//! library). Text and attribute values are escaped by quick-xml.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesText, Event};

/// An XML element with attributes, text and children.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct El {
    name: String,
    attrs: Vec<(String, String)>,
    text: Option<String>,
    children: Vec<El>,
}

impl El {
    /// An element called `name`.
    pub fn new(name: &str) -> El {
        El {
            name: name.to_string(),
            ..El::default()
        }
    }

    /// Adds an attribute.
    pub fn attr(mut self, key: &str, value: impl ToString) -> El {
        self.attrs.push((key.to_string(), value.to_string()));
        self
    }

    /// Sets the text content.
    pub fn text(mut self, text: impl ToString) -> El {
        self.text = Some(text.to_string());
        self
    }

    /// Adds a child.
    pub fn child(mut self, child: El) -> El {
        self.children.push(child);
        self
    }

    /// Adds a child in place.
    pub fn push(&mut self, child: El) {
        self.children.push(child);
    }

    /// Adds children.
    pub fn children(mut self, children: impl IntoIterator<Item = El>) -> El {
        self.children.extend(children);
        self
    }

    /// Shorthand for `<name>text</name>`.
    pub fn leaf(name: &str, text: impl ToString) -> El {
        El::new(name).text(text)
    }

    fn write(&self, w: &mut Writer<Vec<u8>>) -> std::io::Result<()> {
        let mut el = w.create_element(self.name.as_str());
        for (k, v) in &self.attrs {
            el = el.with_attribute((k.as_str(), v.as_str()));
        }
        match (&self.text, self.children.is_empty()) {
            (None, true) => {
                el.write_empty()?;
            }
            (Some(t), true) => {
                el.write_text_content(BytesText::new(t))?;
            }
            (text, false) => {
                el.write_inner_content(|w| {
                    if let Some(t) = text {
                        w.write_event(Event::Text(BytesText::new(t)))?;
                    }
                    for c in &self.children {
                        c.write(w)?;
                    }
                    Ok(())
                })?;
            }
        }
        Ok(())
    }

    /// The document text with an XML declaration, two-space indentation and a final newline.
    pub fn to_document(&self) -> String {
        let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
        // Writing into a Vec cannot fail.
        let _ = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)));
        let _ = self.write(&mut w);
        let mut s = String::from_utf8(w.into_inner()).unwrap_or_default();
        s.push('\n');
        s
    }
}

/// Space-separated numbers, shortest round-trip form.
pub fn nums(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| fmt_num(*v))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A number in its shortest round-trip form, with `-0` written as `0`.
pub fn fmt_num(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v}")
    }
}

/// Parses an XML document into an element tree (comments, declarations and processing
/// instructions dropped; text trimmed; entity and character references resolved).
pub fn parse(text: &str) -> Result<El, String> {
    use quick_xml::XmlVersion;
    use quick_xml::reader::Reader;

    // Text is kept untrimmed so spaces around entity references survive; readers trim.
    let mut reader = Reader::from_str(text);
    let mut stack: Vec<El> = Vec::new();
    let mut root: Option<El> = None;
    let start_el = |e: &quick_xml::events::BytesStart| -> Result<El, String> {
        let mut el = El::new(e.name().as_ref());
        for a in e.attributes() {
            let a = a.map_err(|err| err.to_string())?;
            let v = a
                .normalized_value(XmlVersion::Implicit1_0)
                .map_err(|err| err.to_string())?;
            el.attrs.push((a.key.as_ref().to_string(), v.into_owned()));
        }
        Ok(el)
    };
    let mut close = |el: El, stack: &mut Vec<El>| match stack.last_mut() {
        Some(parent) => parent.children.push(el),
        None => root = Some(el),
    };
    loop {
        let event = reader
            .read_event()
            .map_err(|e| format!("at byte {}: {e}", reader.error_position()))?;
        match event {
            Event::Start(e) => stack.push(start_el(&e)?),
            Event::Empty(e) => {
                let el = start_el(&e)?;
                close(el, &mut stack);
            }
            Event::End(_) => {
                let el = stack.pop().ok_or("unbalanced end tag")?;
                close(el, &mut stack);
            }
            Event::Text(t) => {
                if let Some(top) = stack.last_mut() {
                    let s = t.xml_content(XmlVersion::Implicit1_0);
                    top.text.get_or_insert_with(String::new).push_str(&s);
                }
            }
            Event::CData(t) => {
                if let Some(top) = stack.last_mut() {
                    let s = t.xml_content(XmlVersion::Implicit1_0).into_owned();
                    top.text.get_or_insert_with(String::new).push_str(&s);
                }
            }
            Event::GeneralRef(r) => {
                let resolved = match r.resolve_char_ref().map_err(|e| e.to_string())? {
                    Some(c) => c.to_string(),
                    None => match &*r {
                        "amp" => "&".into(),
                        "lt" => "<".into(),
                        "gt" => ">".into(),
                        "quot" => "\"".into(),
                        "apos" => "'".into(),
                        other => return Err(format!("unknown entity &{other};")),
                    },
                };
                if let Some(top) = stack.last_mut() {
                    top.text.get_or_insert_with(String::new).push_str(&resolved);
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if !stack.is_empty() {
        return Err(format!(
            "unclosed element <{}>",
            stack[stack.len() - 1].name
        ));
    }
    root.ok_or_else(|| "no root element".to_string())
}

impl El {
    /// Element name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Attribute value.
    pub fn get_attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// Trimmed text content ("" when none).
    pub fn text_content(&self) -> &str {
        self.text.as_deref().map(str::trim).unwrap_or("")
    }

    /// First child called `name`.
    pub fn find(&self, name: &str) -> Option<&El> {
        self.children.iter().find(|c| c.name == name)
    }

    /// All children called `name`.
    pub fn find_all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a El> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// Text of the first child called `name`.
    pub fn child_text(&self, name: &str) -> Option<&str> {
        self.find(name).map(El::text_content)
    }

    /// Whitespace-separated numbers in the text of child `name`.
    pub fn child_nums(&self, name: &str) -> Option<Vec<f64>> {
        self.child_text(name).and_then(parse_nums)
    }
}

/// Whitespace-separated numbers; `None` if any token is not a finite number.
pub fn parse_nums(text: &str) -> Option<Vec<f64>> {
    text.split_whitespace()
        .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_text_and_attributes() {
        let doc = El::new("a")
            .attr("name", "x\"<y>")
            .child(El::leaf("b", "1 < 2 & 3"))
            .to_document();
        assert!(doc.contains("&lt;"));
        assert!(doc.contains("&amp;"));
        assert!(doc.contains("name=\"x&quot;&lt;y&gt;\""));
    }
}

#[cfg(test)]
mod parse_tests {
    use super::*;

    #[test]
    fn round_trips_escaped_text_and_attributes() {
        let doc = El::new("a")
            .attr("name", "x\"<y> & z")
            .child(El::leaf("b", "1 < 2 & 3 ☕"))
            .child(El::new("c"))
            .to_document();
        let back = parse(&doc).unwrap();
        assert_eq!(back.get_attr("name"), Some("x\"<y> & z"));
        assert_eq!(back.child_text("b"), Some("1 < 2 & 3 ☕"));
        assert!(back.find("c").is_some());
    }

    #[test]
    fn rejects_broken_documents() {
        assert!(parse("<a><b></a>").is_err());
        assert!(parse("").is_err());
        assert!(parse("<a>&bogus;</a>").is_err());
    }
}
