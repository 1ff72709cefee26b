import { Checkbox, Group, NumberInput, Select, Switch, Text, TextInput } from "@mantine/core";
import { useRef } from "react";
import type { FieldSpec, FieldValue } from "../../lib/schema";

interface FieldInputProps {
  spec: FieldSpec;
  value: FieldValue;
  onChange: (v: FieldValue) => void;
  /** Display unit, e.g. `mm/s` (numbers only). */
  unit: string | null;
  invalid: boolean;
  /** Lands on the <input> element. */
  testId: string;
  id?: string;
  /** Accessible name when no visible <label for> points at the input. */
  ariaLabel?: string;
  disabled?: boolean;
}

function NumberField({ spec, value, onChange, unit, invalid, testId, id, ariaLabel, disabled }: FieldInputProps) {
  const unitWidth = unit ? Math.max(32, Math.round(unit.length * 7) + 22) : 0;
  const noNegative = (spec.min !== null && spec.min >= 0) || (spec.exclusiveMin !== null && spec.exclusiveMin >= 0);
  return (
    <NumberInput
      id={id}
      aria-label={ariaLabel}
      value={typeof value === "boolean" || value === null ? "" : value}
      onChange={(v) => onChange(v)}
      data-testid={testId}
      error={invalid}
      disabled={disabled}
      allowDecimal={spec.kind !== "integer"}
      allowNegative={!noNegative}
      clampBehavior="none"
      thousandSeparator={false}
      rightSection={
        unit ? (
          <Text size="xs" c="dimmed" pr={7} style={{ pointerEvents: "none", whiteSpace: "nowrap" }}>
            {unit}
          </Text>
        ) : undefined
      }
      rightSectionWidth={unit ? unitWidth : undefined}
      rightSectionPointerEvents="none"
      styles={{ input: { fontVariantNumeric: "tabular-nums", textAlign: "right", paddingRight: unit ? unitWidth : undefined } }}
      autoComplete="off"
    />
  );
}

/** A nullable number (a simulated sensor): a number, or "not fitted". */
function NullableNumberField(props: FieldInputProps) {
  const { value, onChange, testId, disabled } = props;
  // The number to restore when "not fitted" is unchecked again.
  const last = useRef<FieldValue>(value === null ? 0 : value);
  const notFitted = value === null;
  return (
    <Group gap={8} wrap="nowrap">
      <div style={{ flex: 1, minWidth: 0 }}>
        {notFitted ? (
          <TextInput
            id={props.id}
            aria-label={props.ariaLabel}
            value=""
            placeholder="not fitted"
            disabled
            data-testid={testId}
            size="xs"
            styles={{ input: { textAlign: "right" } }}
          />
        ) : (
          <NumberField
            {...props}
            onChange={(v) => {
              last.current = v;
              onChange(v);
            }}
          />
        )}
      </div>
      <Checkbox
        size="xs"
        label="Not fitted"
        checked={notFitted}
        disabled={disabled}
        onChange={(e) => {
          if (e.currentTarget.checked && value !== null) last.current = value;
          onChange(e.currentTarget.checked ? null : last.current);
        }}
        data-testid={`${testId}-null`}
        styles={{ label: { paddingLeft: 5, fontSize: 11, whiteSpace: "nowrap" } }}
      />
    </Group>
  );
}

/** The input of one schema field: NumberInput, Select of enumerator names, Switch, or text. */
export function FieldInput(props: FieldInputProps) {
  const { spec, value, onChange, invalid, testId, id, ariaLabel, disabled } = props;
  switch (spec.kind) {
    case "number":
    case "integer":
      return spec.nullable ? <NullableNumberField {...props} /> : <NumberField {...props} />;
    case "enum": {
      const current = typeof value === "string" ? value : null;
      const data = spec.options.map((o) => ({ value: o.name, label: o.name }));
      if (current !== null && !spec.options.some((o) => o.name === current)) data.push({ value: current, label: current });
      const codes = new Map(spec.options.map((o) => [o.name, o.value]));
      return (
        <Select
          id={id}
          aria-label={ariaLabel}
          size="xs"
          data={data}
          value={current}
          onChange={(v) => v !== null && onChange(v)}
          allowDeselect={false}
          error={invalid}
          disabled={disabled}
          data-testid={testId}
          styles={{ input: { fontFamily: "var(--mantine-font-family-monospace)", fontSize: 11, paddingRight: 24 } }}
          rightSectionWidth={24}
          comboboxProps={{ width: "max-content", position: "bottom-end" }}
          renderOption={({ option, checked }) => (
            <Group gap={10} wrap="nowrap" justify="space-between" w="100%">
              <Text size="xs" ff="monospace" fw={checked ? 700 : 400}>
                {option.value}
              </Text>
              {codes.get(option.value) !== null && codes.get(option.value) !== undefined && (
                <Text size="xs" c="dimmed" className="num">
                  {codes.get(option.value)}
                </Text>
              )}
            </Group>
          )}
        />
      );
    }
    case "boolean":
      return (
        <Switch
          id={id}
          aria-label={ariaLabel}
          size="sm"
          checked={value === true}
          onChange={(e) => onChange(e.currentTarget.checked)}
          disabled={disabled}
          data-testid={testId}
          label={
            <Text size="xs" ff="monospace" c={value === true ? "dark" : "dimmed"}>
              {value === true ? "TRUE" : "FALSE"}
            </Text>
          }
          styles={{ body: { alignItems: "center" }, label: { paddingLeft: 8 } }}
        />
      );
    default:
      return (
        <TextInput
          id={id}
          aria-label={ariaLabel}
          size="xs"
          value={typeof value === "string" || typeof value === "number" ? String(value) : ""}
          onChange={(e) => onChange(e.currentTarget.value)}
          error={invalid}
          disabled={disabled}
          data-testid={testId}
        />
      );
  }
}
