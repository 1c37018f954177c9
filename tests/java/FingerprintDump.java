// Prints "<class name> <LCM_FINGERPRINT>" for every class in a types jar,
// loading each one as lcm-spy does (by reflection, from its classpath).
import java.lang.reflect.Field;
import java.util.Enumeration;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;

public class FingerprintDump {
    public static void main(String[] args) throws Exception {
        try (JarFile jar = new JarFile(args[0])) {
            Enumeration<JarEntry> entries = jar.entries();
            while (entries.hasMoreElements()) {
                String name = entries.nextElement().getName();
                if (!name.endsWith(".class") || name.contains("$")) continue;
                String cls = name.substring(0, name.length() - 6).replace('/', '.');
                Field f = Class.forName(cls).getField("LCM_FINGERPRINT");
                System.out.println(cls + " " + f.getLong(null));
            }
        }
    }
}
